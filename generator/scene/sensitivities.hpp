// rotgen — the scene's `sensitivities:` key: which derivatives of the motion a run integrates with
// it (the variational equations, run/sensitivity_run.hpp).
//
//   sensitivities: [initial.theta, initial.psi_dot, parameters.h]
//   sensitivities: {keys: [initial.theta, parameters.h], error_control: true}
//   sensitivities: {keys: all_initial}    # every component of the run form's state at t0
//
// A key is one `sweep` accepts (scene/value_keys.hpp), with sweep's meaning: a parameter key holds
// the other initial values at their numbers. `all_initial` names the keys y0.<state name>, in the
// order of the run form's state: S is then the state-transition matrix. error_control (default
// true) puts S in the step's error estimate (as CVODES' errconS); false controls the state alone.
// Integrated by dop853, dopri5, rk4 and taylor (the recurrences of (y, S):
// run/taylor_sensitivity.hpp); refused (located) with every other method.
#pragma once

#include "scene/value_keys.hpp"

#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace rotgen {

struct sensitivity_spec {
    std::vector<value_key> keys; // as written (none with all_initial)
    bool all_initial = false;
    bool error_control = true;
    source_location where; // the `sensitivities:` entry
    bool active() const { return all_initial || !keys.empty(); }
};

// The methods that integrate sensitivities, in words ("dop853, dopri5, rk4 or taylor").
bool method_takes_sensitivities(const std::string& method);
std::string sensitivity_methods();

// Reads the `sensitivities:` node `n` of the scene (its model, `initial` and integrator read):
// user_error, located, for a key no sweep accepts, a key given twice, an empty list, an unknown
// field, a method that does not take sensitivities, a linear rotor.
sensitivity_spec read_sensitivities(const YAML::Node& n, const scene_spec& scene,
                                    const std::string& file);

} // namespace rotgen
