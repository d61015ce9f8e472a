// rotgen — the run engine: scene -> derived model -> the form's kernels (emitted, compiled,
// loaded) -> integrated with the runtime, sampled at the scene's times -> recorded columns and
// invariant drifts. `rotgen simulate` writes what it returns; nothing here writes files.
//
// Gimbal lock: the Lagrangian and Hamiltonian forms are singular at theta = 0, pi (det J =
// -sin theta, 5.30). Unless the scene says `switch_chart: false`, a run in those forms continues in
// the body form (quaternion and omega, no singularity) from the first sample where |sin theta| <
// 0.1, or from the last sample when the Euler-angle integration fails, provided the model's body
// form does not itself go through the Euler-angle chart; a scene that starts there starts in the
// body form. A linear rotor's form (rotor) does the same with its second chart, rotor_x
// (run/rotor_chart.hpp), when its potential depends on the angles through cos(theta) alone.
#pragma once

#include "derive/derive.hpp"
#include "run/kernels.hpp"
#include "run/sample_states.hpp"
#include "scene/scene.hpp"
#include "support/timings.hpp"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace rotgen {

struct invariant_drift {
    invariant what;
    double first = 0;   // at the first sample
    double drift = 0;   // max |v(t) - v(t0)| over the samples (and the state where a run
                        // that could not finish stopped)
    double largest = 0; // max |v(t)| over the samples: the scale `first` is compared with
};

struct run_result {
    form_kind form = form_kind::lagrangian; // the first form run: the scene's, or the body form
                                            // (a split method, a start at the gimbal lock)
    std::size_t state_size = 0;             // of that form
    std::vector<std::string> record;        // the recorded quantities (the scene's, or its default)
    std::vector<std::string> columns;       // the recorded columns, after t (body_x expands to 3)
    std::vector<std::vector<double>> rows;  // t, then one value per column, per sample
    std::vector<invariant_drift> invariants; // within each segment between actions (their
                                             // drift: the largest, from the segment's start)
    std::size_t segments = 1;                // 1 + the number of actions
    step_stats stats;
    // Events (the scene's `events:`), in time order: which (index into event_names) and the row
    // t, then the recorded columns at the event, as in `rows`.
    std::vector<std::string> event_names;
    std::vector<std::size_t> event_index;
    std::vector<std::vector<double>> event_rows;
    // Per event row: "before" or "after" for an action (impulse, set: a row each), "" otherwise.
    std::vector<std::string> event_phase;
    int stopped_by = -1; // the terminal event that ended the run (its state is the last row)
    // Where a pair of zeros of an event may hide: the search could neither prove nor exclude a
    // sign change there (runtime/integrate/event_roots.hpp).
    struct event_doubt {
        std::size_t index;
        double from, to;
    };
    std::vector<event_doubt> event_doubts;
    std::string chart_note; // the chart switch, if one happened (empty otherwise)
    bool ok = true;         // the integration reached the end time
    double t_reached = 0;   // where the steps taken ended: the last row's t, or (!ok) the time
                            // the run stopped at, after it (`invariants` include that state)
    std::string message;    // why not, when !ok
    double integrate_seconds = 0;
    // With the scene's sensitivities (run/sensitivity_run.hpp): the keys (k of them); the columns
    // d(<column>)/d(<key>), record order then key order, of every recorded column (the attitude
    // and the body form's angles too); per row of `rows`, their values and the state's
    // sensitivity S = dy/ds (n x k, row-major: S[i * k + j] = d y_i/d key_j, y the state of
    // `form`).
    std::vector<std::string> sensitivity_keys, sensitivity_columns;
    std::vector<std::vector<double>> sensitivity_rows, state_sensitivities;
    // Per event row: d(t_event)/d(<key>) for each key, then the recorded columns' derivatives
    // with the state's sensitivity at the event, S + f dt_e/ds (named in that order). A terminal
    // event's sample row carries the same.
    std::vector<std::string> event_sensitivity_columns;
    std::vector<std::vector<double>> event_sensitivity_rows;
    bool kernels_cached = true; // every compiled form came from the cache
};

// Called at each sample with its time (e.g. to show progress); may be empty.
using sample_callback = std::function<void(double t)>;

// Runs the scene (prepare_scene, then run_member with the scene's own values). Throws user_error
// for a scene the model cannot run (an unrecordable quantity, a start at the singularity that
// cannot be left, initial values that overflow double).
run_result run_scene(const scene_spec& scene, stage_timings& timings,
                     const sample_callback& on_sample = {});

class prepared_scene; // run/prepared.hpp: derivation and compiled kernels, shared by members

// What a member of an ensemble sets: the initial angles (z-x-z, radians), the initial rates (as
// the scene's `initial` gives them: q_dot, p or body omega) and the model's parameters (in model
// order). Everything else is the prepared scene's.
struct member_values {
    std::array<double, 3> angles{}, initial_rates{};
    std::vector<double> parameters;
};
member_values values_of(const scene_spec& scene);

// Runs one member on a prepared scene. Thread-safe: members may run concurrently on one prepared
// scene (each with its own `timings`). Throws user_error as run_scene does, for this member.
run_result run_member(const prepared_scene& prepared, const member_values& values,
                      stage_timings& timings, const sample_callback& on_sample = {});

// The sample times: `samples` points from t_start to t_end, the last exactly t_end (or the
// scene's explicit `sample_at`).
std::vector<double> sample_times(const scene_spec& scene);

// An event a member met in a run integrated elsewhere: which of the scene's events, when, and the
// state there.
struct member_event {
    std::size_t index;
    double t;
    Eigen::VectorXd y;
};

// A member's run in parts, for lanes (run/lanes.hpp) that integrate several members together:
// start() as run_member starts (the same user errors), giving the state and the parameter values
// of the scene's form, or false when the member starts in the body form (then only run_member can
// run it); keeps_chart(k, t, y): false when run_member would leave the chart at its k-th sample
// (t, y) of the first form; finish() gives run_member's result from the samples of the whole run
// in the first form, integrated elsewhere with the work counters `stats`: t_start .. t_end, or
// to the time of the terminal event `stopped_by` (-1: none) among `events` (in time order).
class member_parts {
  public:
    virtual ~member_parts() = default;
    virtual bool start(Eigen::VectorXd& y0, std::vector<double>& parameters) = 0;
    virtual bool keeps_chart(std::size_t sample, double t, const Eigen::VectorXd& y) const = 0;
    virtual run_result finish(const sample_states& samples, const step_stats& stats,
                              std::vector<member_event> events, int stopped_by) = 0;
};
std::unique_ptr<member_parts> run_parts(const prepared_scene& prepared, const member_values& values,
                                        stage_timings& timings);

// Whether the body form must keep the orientation (the quaternion) for this scene: a chart switch,
// or a recorded angle, body axis, Euler-angle rate or momentum, quaternion or space-axes L needs
// it. (A potential that needs it makes the body form keep it anyway.) One rule for simulate and
// bench.
bool needs_orientation(const scene_spec& scene, bool chart_switch);

} // namespace rotgen
