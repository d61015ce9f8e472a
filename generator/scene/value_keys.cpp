#include "scene/value_keys.hpp"

#include "scene/scene.hpp"
#include "support/format.hpp"

#include <array>

namespace rotgen {

std::vector<std::string> initial_names(const scene_spec& scene) {
    const auto& q = scene.model.angles.names;
    const std::array<std::array<std::string, 3>, 3> rates{
        {{q[0] + "_dot", q[1] + "_dot", q[2] + "_dot"},
         {"p_" + q[0], "p_" + q[1], "p_" + q[2]},
         {"omega1", "omega2", "omega3"}}};
    std::vector<std::string> names(q.begin(), q.end());
    for (const auto& r : rates[static_cast<std::size_t>(scene.initial)])
        names.push_back(r);
    return names;
}

void resolve_value_key(const scene_spec& scene, value_key& k, const std::string& what) {
    const auto dot = k.key.find('.');
    const std::string group = k.key.substr(0, dot),
                      name = dot == std::string::npos ? std::string() : k.key.substr(dot + 1);
    std::vector<std::string> names;
    if (group == "initial") {
        names = initial_names(scene);
        for (std::size_t i = 0; i < names.size(); ++i)
            if (names[i] == name) {
                if (scene.model.rotor && i % 3 == 2) // psi, psi_dot: no coordinate of a rotor
                    throw user_error(k.where, what + " '" + k.key +
                                                  "': a linear rotor's state is phi, theta, "
                                                  "phi_dot, theta_dot");
                k.target = i < 3 ? value_key::angle : value_key::rate;
                k.index = i % 3;
                return;
            }
    } else if (group == "parameters") {
        for (std::size_t i = 0; i < scene.model.parameters.size(); ++i) {
            names.push_back(scene.model.parameters[i].name);
            if (names.back() == name) {
                k.target = value_key::parameter;
                k.index = i;
                return;
            }
        }
    } else {
        throw user_error(k.where, "unknown " + what + " '" + k.key +
                                      "' (expected initial.<name> or parameters.<name>)");
    }
    std::vector<std::string> keys;
    for (const auto& n : names)
        keys.push_back(group + "." + n);
    const std::string best = closest_name(k.key, keys);
    throw user_error(k.where, "unknown " + what + " '" + k.key + "' for this scene" +
                                  (best.empty() ? "" : "; did you mean '" + best + "'?"));
}

} // namespace rotgen
