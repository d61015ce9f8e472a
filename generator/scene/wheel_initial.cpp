// rotgen — scene/: a free wheel's axial momentum in `initial` (initial_input.hpp). The momentum
// p_<wheel> = J (a . omega + <wheel>_dot) of a free wheel is conserved: the model holds it as a
// parameter (spec/wheels_input.cpp), and `initial: {p_wheel: 2}` sets that parameter.
#include "scene/initial_input.hpp"

namespace rotgen::scene_detail {

std::string wheel_momenta_refusal(const model_spec& model, const std::string& instead) {
    return "model '" + model.name + "' carries wheels: " + instead + " (its momenta p_" +
           model.angles.names[0] + ".. include the wheels' h)";
}

void read_wheel_initial(scene_spec& scene, const YAML::Node& n, const YAML::Node& parameters,
                        const value_reader& values, const std::string& file) {
    if (!scene.model.wheels.empty() && scene.initial == initial_kind::momenta)
        throw user_error(scene.initial_where,
                         wheel_momenta_refusal(scene.model, "give the initial rates as the "
                                                            "angles' rates or omega"));
    const auto& ps = scene.model.parameters;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        if (!ps[i].wheel_momentum || !n[ps[i].name]) continue;
        if (parameters && parameters.IsMap() && parameters[ps[i].name])
            throw user_error(location_of(n[ps[i].name], file),
                             "'" + ps[i].name + "' is given in both 'parameters' and 'initial'");
        const written_value v = values.value(n[ps[i].name], "initial " + ps[i].name);
        scene.parameters[i] = v.value;
        scene.parameters_written[i] = v;
    }
}

void check_wheel_scene(const scene_spec& scene) {
    if (scene.model.wheels.empty() || scene.form != form_kind::hamiltonian || !scene.switch_chart)
        return;
    throw user_error(scene.where, "model '" + scene.model.name +
                                      "' carries wheels: its hamiltonian form cannot switch "
                                      "charts (the body form's momenta would lack h); write "
                                      "switch_chart: false, or use the lagrangian or body form");
}

} // namespace rotgen::scene_detail
