// rotgen — the `events:` list of a scene file (DESIGN.md "Interfaces"): zeros of expressions,
// located on the dense output by the runtime (runtime/integrate/events.hpp).
//
//   events:
//     - name: floor                # required, unique; names the event in outputs
//       when: theta - pi/2         # an event is a zero of this expression
//       direction: rising          # rising | falling | both (default both)
//       action: stop               # stop | record (default record), or an action that changes
//                                  # the state (scene/event_actions.hpp)
//     - name: pulse
//       every: 0.5                 # a time event: t = start + k 0.5, k >= 1 (instead of `when`)
//       action: {impulse: [0, 0, kick]}
//       after: 2                   # act (or record, or stop) from the 2nd occurrence on
//
// `when` is written in the model language over the states and rates (phi, theta, psi, phi_dot,
// .., p_phi, .., omega1..3), every scalar record name (energy, ...), t, and the model's
// parameters. The form that integrates must give every name used (run/ checks it).
#pragma once

#include "inspect/inspect.hpp"
#include "spec/spec.hpp"

#include <ginac/ginac.h>

#include <array>
#include <string>
#include <vector>

namespace rotgen {

// What an event does when it occurs (from its `after`-th occurrence on).
enum class action_kind { record, stop, impulse, impulse_space, set };

// One `set:` entry: a state name of one way of `initial:` (the angles, q0..q3, A, the rates,
// momenta, omega1..3, omega_x..z) or `parameters.<name>`, and its new value(s): one expression, or
// nine for A (row by row), in the names of action_names().
struct set_entry {
    std::string name; // as written (`parameters.k` included)
    std::vector<GiNaC::ex> values;
    source_location where; // the key
};

struct event_spec {
    std::string name;
    std::string when_text; // as written (empty for a time event)
    GiNaC::ex when;        // in the symbols of event_names(); a time event's is the constant 1
    int direction = 0;     // +1 rising, -1 falling, 0 both
    bool stop = false;     // action: stop (a terminal event)
    source_location where; // the `when` (or `every`) expression
    // `every: T`: a time event at t = every_origin + k T, k >= 1; T in the model's parameters.
    bool periodic = false;
    GiNaC::ex every;
    double every_origin = 0; // the scene's own time.start (kept across `simulate --from`)
    long after = 1;          // acts (records, stops) from this occurrence on
    action_kind action = action_kind::record;
    std::array<GiNaC::ex, 3> impulse; // impulse, impulse_space: J, in the names of action_names()
    std::vector<set_entry> set;
    source_location action_where; // the `action` value
    // Whether the event changes the state or the parameters (impulse, impulse_space, set).
    bool acts() const { return action != action_kind::record && action != action_kind::stop; }
};

// The names an action's values may use: the state before the event (angles, rates, momenta,
// omega1..3), t and the model's parameters (the symbols of event_names()).
name_table action_names(const model_spec& model);

// The names an event expression may use for `model`, with their symbols: the coordinate, rate,
// momentum and omega symbols of expr/symbols, t, the model's parameters, and one symbol per other
// scalar record name (made once and never changed, so that run/ substitutes the form's expression
// for it).
name_table event_names(const model_spec& model);

// Reads the scene's `events:` list (absent: none). Throws user_error with the location.
// `t_start` is the scene's time.start, the origin of `every`.
std::vector<event_spec> read_events(const YAML::Node& n, const model_spec& model,
                                    const std::string& file, double t_start);

// "record", "stop", "impulse", "impulse_space", "set".
const char* action_name(action_kind a);

// "rising", "falling", "both".
const char* direction_name(int direction);

// The events for `rotgen inspect SCENE`: text and LaTeX, a section to print after the model's;
// JSON, the members `"events": [{name, when, direction, action}]` to add to inspect's object. The
// coordinates are shown by the names of `angles`, the model's convention.
std::string describe_events(const std::vector<event_spec>& events, const angle_convention& angles,
                            output_format format);

} // namespace rotgen
