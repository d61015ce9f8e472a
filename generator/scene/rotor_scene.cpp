// rotgen — scene/: a linear rotor's scene (rotor_scene.hpp).
#include "scene/rotor_scene.hpp"

#include <array>

namespace rotgen::scene_detail {

void check_rotor_form(const scene_spec& scene, const YAML::Node& n, const std::string& file) {
    const model_spec& m = scene.model;
    if (m.rotor && scene.form != form_kind::rotor)
        throw user_error(location_of(n, file), "model '" + m.name +
                                                   "' is a linear rotor (Example 5.4): its form is "
                                                   "'rotor' (two angles phi, theta), not " +
                                                   to_string(scene.form));
    if (!m.rotor && scene.form == form_kind::rotor)
        throw user_error(location_of(n, file), "form 'rotor' is the form of a linear rotor; "
                                               "model '" +
                                                   m.name + "' is not one");
}

void read_rotor_initial(scene_spec& scene, const YAML::Node& n, const source_location& key,
                        const value_reader& values, const std::string& file) {
    const std::array<std::string, 4> names{"phi", "theta", "phi_dot", "theta_dot"};
    for (const auto& kv : n) {
        const std::string k = kv.first.IsScalar() ? kv.first.Scalar() : "";
        bool known = false;
        for (const auto& name : names)
            known = known || k == name;
        if (!known)
            throw user_error(location_of(kv.first, file),
                             "a linear rotor's initial state is phi, theta, phi_dot, theta_dot "
                             "(the direction of its line and its rates); '" +
                                 k + "' is not part of it");
    }
    std::string missing;
    for (const auto& name : names)
        if (!n[name]) missing += (missing.empty() ? "" : ", ") + name;
    if (!missing.empty())
        throw user_error(key, "the initial state is incomplete: missing " + missing +
                                  " (a rotor's state is phi, theta, phi_dot, theta_dot; nothing "
                                  "defaults to 0)");
    for (std::size_t i = 0; i < 2; ++i) {
        scene.angles_written[i] = values.value(n[names[i]], "initial " + names[i]);
        scene.angles[i] = scene.angles_written[i].value;
        scene.rates_written[i] = values.value(n[names[2 + i]], "initial " + names[2 + i]);
        scene.initial_rates[i] = scene.rates_written[i].value;
    }
    scene.angles_written[2] = scene.rates_written[2] = written_value{};
    scene.angles[2] = scene.initial_rates[2] = 0;
    scene.initial = initial_kind::rates;
}

std::string rotor_unrecordable(const std::string& name) {
    const std::string none = "a linear rotor has no body axes beyond its line";
    if (name == "psi" || name == "psi_dot" || name == "p_psi")
        return "psi, the turn about the line, is not a coordinate of a rotor (it moves no mass)";
    if (name.rfind("omega", 0) == 0 || name.rfind("body_", 0) == 0)
        return none + " (its angular velocity across the line is L / I, recorded as Lx, Ly, Lz)";
    if (name == "L1" || name == "L2" || name == "L3") return none + "; record Lx, Ly, Lz";
    if (name.size() == 2 && name[0] == 'q')
        return "a rotor's attitude is its line's direction, not a rotation (no quaternion)";
    return "";
}

void check_rotor_integrator(const scene_spec& scene) {
    const std::string& m = scene.integrator.method;
    if (m == "split2" || m == "split4" || m == "split6")
        throw user_error(scene.integrator_where,
                         "integrator " + m +
                             " steps a three-axis body (Euler's equations); a "
                             "linear rotor has two angles: use dop853, dopri5, rk4, "
                             "implicit_midpoint, rosenbrock or taylor");
}

} // namespace rotgen::scene_detail
