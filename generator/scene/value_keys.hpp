// rotgen — keys that name one of a scene's values, as `sweep: vary:` and `sensitivities:` write
// them: `initial.<name>` for an angle or a rate the scene's `initial` gives (phi, theta, psi and
// phi_dot.., p_phi.. or omega1..3, whichever it gives) and `parameters.<name>` for a parameter of
// the model. One parser for both (sweep/members.hpp, scene/sensitivities.hpp).
#pragma once

#include "support/error.hpp"

#include <string>
#include <vector>

namespace rotgen {

struct scene_spec;

// What a key sets: an initial angle (index 0..2), an initial rate (0..2, as `initial` gives the
// rates) or a model parameter (its index in model order).
struct value_key {
    std::string key;       // as written: "initial.theta", "parameters.h"
    source_location where; // where it was written
    enum target_t { angle, rate, parameter } target = angle;
    std::size_t index = 0;
};

// The names `initial.<name>` may use in this scene: the angles and the rates it gives.
std::vector<std::string> initial_names(const scene_spec& scene);

// Resolves k.key to what it sets in the scene (k.target, k.index). Throws user_error at k.where,
// calling the key `what` ("sweep key"), when it sets nothing, with the closest key suggested.
void resolve_value_key(const scene_spec& scene, value_key& k, const std::string& what);

} // namespace rotgen
