#include "scene/sensitivities.hpp"

#include "scene/scene.hpp"
#include "spec/spec.hpp"

#include <yaml-cpp/yaml.h>

namespace rotgen {

bool method_takes_sensitivities(const std::string& method) {
    return method == "dop853" || method == "dopri5" || method == "rk4" || method == "taylor";
}

std::string sensitivity_methods() {
    return "dop853, dopri5, rk4 or taylor";
}

namespace {

void read_keys(const YAML::Node& n, const scene_spec& scene, const std::string& file,
               sensitivity_spec& s) {
    if (n.IsScalar() && n.Scalar() == "all_initial") {
        s.all_initial = true;
        return;
    }
    if (!n.IsSequence() || n.size() == 0)
        throw user_error(location_of(n, file),
                         "sensitivities: keys must be a non-empty list of keys (initial.<name>, "
                         "parameters.<name>) or all_initial");
    for (const YAML::Node& item : n) {
        value_key k;
        k.where = location_of(item, file);
        if (!item.IsScalar())
            throw user_error(k.where, "a sensitivity key must be initial.<name> or "
                                      "parameters.<name>");
        k.key = item.Scalar();
        resolve_value_key(scene, k, "sensitivity key");
        for (const value_key& old : s.keys)
            if (old.key == k.key)
                throw user_error(k.where, "sensitivity key '" + k.key + "' given twice");
        s.keys.push_back(std::move(k));
    }
}

} // namespace

sensitivity_spec read_sensitivities(const YAML::Node& n, const scene_spec& scene,
                                    const std::string& file) {
    sensitivity_spec s;
    if (!n) return s;
    s.where = location_of(n, file);
    if (n.IsMap()) {
        check_keys(n, {"keys", "error_control"}, file, "sensitivities");
        if (!n["keys"]) throw user_error(s.where, "sensitivities: missing field 'keys'");
        read_keys(n["keys"], scene, file, s);
        if (const YAML::Node e = n["error_control"]) {
            if (!e.IsScalar() || (e.Scalar() != "true" && e.Scalar() != "false"))
                throw user_error(location_of(e, file), "error_control must be true or false");
            s.error_control = e.Scalar() == "true";
        }
    } else {
        read_keys(n, scene, file, s);
    }
    if (scene.model.rotor)
        throw user_error(s.where, "sensitivities are not integrated for a linear rotor");
    if (scene.integrator.method != "auto" && !method_takes_sensitivities(scene.integrator.method))
        throw user_error(s.where, "integrator " + scene.integrator.method +
                                      " does not integrate sensitivities; use " +
                                      sensitivity_methods());
    for (const event_spec& e : scene.events) // S would jump too: S+ = h_y S- + ... (not built)
        if (e.acts())
            throw user_error(s.where, "sensitivities are not carried across an event's action "
                                      "(event '" +
                                          e.name + "' at line " +
                                          std::to_string(e.action_where.line) +
                                          " acts); run them without the action");
    if (!s.error_control && !(scene.integrator.atol > 0) && scene.integrator.method != "rk4" &&
        scene.integrator.method != "auto")
        throw user_error(s.where, "error_control: false needs atol > 0");
    return s;
}

} // namespace rotgen
