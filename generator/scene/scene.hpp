// rotgen — scene files: what `rotgen simulate` runs (DESIGN.md "Interfaces").
//
//   model: heavy_top.yaml        # path relative to the scene file, or an inline model mapping
//   parameters: {M: 2.0}         # overrides of the model's defaults
//   form: lagrangian             # lagrangian | hamiltonian | reduced | body | rotor (a rotor)
//   initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 10}
//                                # angles with rates, or with p_phi.., or with omega1..3
//   time: {start: 0, end: 100, samples: 1001}
//   integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}   # rk4/implicit_midpoint: {step: 1e-3}
//   record: [theta, omega1, omega2, omega3, energy, p_phi, p_psi]
//   events: [{name: floor, when: theta - pi/2, direction: rising, action: stop}]   (events.hpp)
//   switch_chart: true           # continue in the body form near theta = 0, pi (default true)
//   sweep: {...}                 # for `rotgen sweep` only (read by sweep/members.hpp)
//   sensitivities: [initial.theta, parameters.h]   # d(motion)/d(key) (sensitivities.hpp)
//
// Angles: z-x-z Euler angles in radians, theta in [0, pi]; rates in rad per time unit; omega in
// body axes.
#pragma once

#include "forms/form_kind.hpp"
#include "scene/events.hpp"
#include "scene/sensitivities.hpp"
#include "spec/spec.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace rotgen {

enum class initial_kind { rates, momenta, omega };

// A value as the scene wrote it (a parameter override or an initial value): a number, or an
// expression of the model language (`pi/2`, `2*pi*f` with the model's parameters), kept exact
// (rationals, pi, functions of them) so that run/kinematics computes from it at 30 digits.
struct written_value {
    double value = 0;        // the double (an expression: its value rounded once)
    GiNaC::ex exact;         // an expression's exact value (parameters put in); unused otherwise
    bool expression = false; // not a plain decimal number
};

struct integrator_spec {
    std::string method = "dop853"; // rk4 | dopri5 | dop853 | implicit_midpoint | rosenbrock |
                                   // split2 | split4 | split6 (step, or rtol: a step by rule) |
                                   // taylor | auto (tune/: chosen before the run)
    double rtol = 1e-8, atol = 1e-10;
    double error = 0; // method auto: the largest error accepted at the samples (tune/tune.hpp)
    // After tune/ resolved `auto` into the method above: "dop853 rtol 3e-9 in the body form
    // (tuned in 4.2 s; cached)", what the summaries print after "auto: "; empty otherwise.
    std::string auto_choice;
    double step = 0; // the step of rk4 and implicit_midpoint; an adaptive method given a step
                     // takes fixed steps of that size without error control (and no rtol, atol)
    long max_steps = 10'000'000;
    bool fixed_step() const { return method == "rk4" || method == "implicit_midpoint" || step > 0; }
};

// The last row of an earlier run's CSV that a run continues from (run/continue_from.hpp).
struct start_row {
    std::string file;               // the CSV
    int line = 0;                   // the row's line in it
    std::vector<std::string> names; // the CSV's header: t, then the recorded columns
    std::vector<double> values;     // the row, one value per name
};

struct scene_spec {
    std::string file;
    model_spec model;
    std::vector<double> parameters; // the model's parameters, in model order, with overrides
    form_kind form = form_kind::lagrangian;
    bool form_given = false;        // the scene wrote `form:` (method auto keeps it)
    std::array<double, 3> angles{}; // phi, theta, psi
    initial_kind initial = initial_kind::rates;
    std::array<double, 3> initial_rates{}; // q_dot, p, or omega, as `initial` says
    // As written (parameters: the overrides; others are the model's defaults, numbers). The
    // exact value stands for the double beside it only while that double is still `value`
    // (run/kinematics: exact_scene_value).
    std::vector<written_value> parameters_written;
    std::array<written_value, 3> angles_written, rates_written;
    double t_start = 0, t_end = 1; // t_end < t_start: the run goes backward in time
    long samples = 101;
    integrator_spec integrator;
    std::vector<std::string> record; // quantities, in order (body_z expands to 3 columns)
    bool record_default = false; // no `record:`: phi, theta, psi, energy, as the form gives them
    // Leave the Euler-angle chart for the body form near theta = 0, pi (lagrangian and
    // hamiltonian forms); `switch_chart: false` keeps the chart (to measure its failure).
    bool switch_chart = true;
    std::vector<event_spec> events; // zeros of expressions located along the run (events.hpp)
    // `simulate --from`: the row the run starts from (its t is t_start; angles and rates were set
    // from it); the body form's attitude is its q0..q3 as written, not the angles'.
    std::optional<start_row> from;
    // Explicit sample times (`rotgen fit`: the measurement times), ascending, inside the span;
    // empty: `samples` times evenly from t_start to t_end (run/engine.hpp's sample_times).
    std::vector<double> sample_at;
    sensitivity_spec sensitivities; // derivatives integrated with the motion (sensitivities.hpp)

    // Where things were written, for errors found later (an unrecordable quantity, a failed run).
    source_location where;            // the scene file itself
    source_location initial_where;    // the `initial` mapping
    source_location integrator_where; // the `integrator` mapping (or the file)
    source_location time_where;       // the time's `end`
    std::vector<source_location> record_where;
};

// The names `record` accepts (the angles' names c's), with the columns each one expands to; those
// that are the same for every convention (omega1, energy, q0, Lx, T, ...).
std::vector<std::string> recordable_names(const angle_convention& c);
const std::vector<std::string>& convention_free_records();
std::vector<std::string> record_columns(const std::string& name);

// The scene recording also `extra` (those it does not record already), each located at the scene
// file; the run's rows then hold them beside the scene's own columns.
scene_spec with_records(const scene_spec& scene, const std::vector<std::string>& extra);

// Reads and validates a scene file (and the model it names). Throws user_error; a model file (one
// with `inertia:` or `body:` and no `model:`) is refused with a message that says so and names
// `command`, the command that takes a scene ("simulate").
scene_spec load_scene(const std::string& path, const std::string& command = "this command");

} // namespace rotgen
