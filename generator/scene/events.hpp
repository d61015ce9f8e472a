// rotgen — the `events:` list of a scene file (DESIGN.md "Interfaces"): zeros of expressions,
// located on the dense output by the runtime (runtime/integrate/events.hpp).
//
//   events:
//     - name: floor                # required, unique; names the event in outputs
//       when: theta - pi/2         # an event is a zero of this expression
//       direction: rising          # rising | falling | both (default both)
//       action: stop               # stop | record (default record)
//
// `when` is written in the model language over the states and rates (phi, theta, psi, phi_dot,
// .., p_phi, .., omega1..3), every scalar record name (energy, ...), t, and the model's
// parameters. The form that integrates must give every name used (run/ checks it).
#pragma once

#include "inspect/inspect.hpp"
#include "spec/spec.hpp"

#include <ginac/ginac.h>

#include <string>
#include <vector>

namespace rotgen {

struct event_spec {
    std::string name;
    std::string when_text; // as written
    GiNaC::ex when;        // in the symbols of event_names()
    int direction = 0;     // +1 rising, -1 falling, 0 both
    bool stop = false;     // action: stop (a terminal event)
    source_location where; // the `when` expression
};

// The names an event expression may use for `model`, with their symbols: the coordinate, rate,
// momentum and omega symbols of expr/symbols, t, the model's parameters, and one symbol per other
// scalar record name (made once and never changed, so that run/ substitutes the form's expression
// for it).
name_table event_names(const model_spec& model);

// Reads the scene's `events:` list (absent: none). Throws user_error with the location.
std::vector<event_spec> read_events(const YAML::Node& n, const model_spec& model,
                                    const std::string& file);

// "rising", "falling", "both".
const char* direction_name(int direction);

// The events for `rotgen inspect SCENE`: text and LaTeX, a section to print after the model's;
// JSON, the members `"events": [{name, when, direction, action}]` to add to inspect's object. The
// coordinates are shown by the names of `angles`, the model's convention.
std::string describe_events(const std::vector<event_spec>& events, const angle_convention& angles,
                            output_format format);

} // namespace rotgen
