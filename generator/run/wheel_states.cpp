// rotgen — run/: a torque-driven wheel's momentum p_<wheel>, a state of the run (kinematics.hpp;
// derive/wheels.hpp): at the start its parameter's value (the scene's `initial` p_<wheel> or
// <wheel>_dot, or `--from`), after a change of chart the state the run had reached.
#include "run/kinematics.hpp"

namespace rotgen {

void start_wheel_states(const scene_spec& scene, const std::vector<long double>& model_values,
                        initial_kinematics& k) {
    const auto& ps = scene.model.parameters;
    k.wheels.clear();
    for (std::size_t i = 0; i < ps.size() && i < model_values.size(); ++i)
        if (ps[i].wheel_state) k.wheels.emplace_back(ps[i].name, model_values[i]);
}

void carry_wheel_states(const scene_spec& scene, const form_expressions& f,
                        const Eigen::VectorXd& y, initial_kinematics& k) {
    k.wheels.clear();
    for (const parameter& p : scene.model.parameters)
        for (std::size_t s = 0; p.wheel_state && s < f.state.size(); ++s)
            if (f.state[s].name == p.name)
                k.wheels.emplace_back(p.name, y[static_cast<Eigen::Index>(s)]);
}

} // namespace rotgen
