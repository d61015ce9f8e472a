// rotgen — scene/: a free wheel's axial momentum in `initial` (initial_input.hpp). The momentum
// p_<wheel> = J (a . omega + <wheel>_dot) of a free wheel is conserved: the model holds it as a
// parameter (spec/wheels_input.cpp), and `initial: {p_wheel: 2}` sets that parameter.
#include "scene/initial_input.hpp"

#include "expr/angles.hpp"
#include "expr/symbols.hpp"

#include <cmath>

namespace rotgen::scene_detail {

namespace {

double number(const GiNaC::ex& e, const GiNaC::exmap& at) {
    const GiNaC::ex v = GiNaC::evalf(e.subs(at));
    return GiNaC::is_a<GiNaC::numeric>(v) ? GiNaC::ex_to<GiNaC::numeric>(v).to_double() : NAN;
}

// p = J (a . omega0 + rate) for the wheel `name`: omega0 the scene's initial body omega (given, or
// J(q) q_dot of (5.30) from the angles and their rates), J and a at the scene's parameter values.
double wheel_momentum_of(const scene_spec& scene, const std::string& name, double rate) {
    const auto& s = symbols();
    GiNaC::exmap at;
    for (std::size_t i = 0; i < scene.model.parameters.size(); ++i)
        at[scene.model.parameters[i].symbol] = GiNaC::numeric(scene.parameters[i]);
    std::array<double, 3> w = scene.initial_rates;
    if (scene.initial == initial_kind::rates) {
        GiNaC::exmap q;
        for (int i = 0; i < 3; ++i)
            q[s.q[i]] = GiNaC::numeric(scene.angles[static_cast<std::size_t>(i)]);
        const ex_matrix3 J = omega_jacobian_of(scene.model.angles);
        for (int i = 0; i < 3; ++i) {
            w[static_cast<std::size_t>(i)] = 0;
            for (int j = 0; j < 3; ++j)
                w[static_cast<std::size_t>(i)] +=
                    number(J[i][j], q) * scene.initial_rates[static_cast<std::size_t>(j)];
        }
    }
    for (const wheel_spec& wheel : scene.model.wheels) {
        if (wheel.name != name) continue;
        double axial = rate;
        for (int i = 0; i < 3; ++i)
            axial += number(wheel.axis[i], at) * w[static_cast<std::size_t>(i)];
        return number(wheel.inertia, at) * axial;
    }
    return NAN;
}

} // namespace

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
        if (!ps[i].wheel_momentum) continue;
        const std::string rate = ps[i].name.substr(2) + "_dot";
        const YAML::Node given = n[ps[i].name] ? n[ps[i].name] : n[rate];
        if (!given) continue;
        if (n[ps[i].name] && n[rate])
            throw user_error(location_of(n[rate], file), "give the wheel's momentum '" +
                                                             ps[i].name + "' or its rate '" + rate +
                                                             "', not both");
        if (parameters && parameters.IsMap() && parameters[ps[i].name])
            throw user_error(location_of(given, file), "'" + ps[i].name +
                                                           "' is given in both 'parameters' and "
                                                           "'initial'");
        if (n[ps[i].name]) {
            const written_value v = values.value(given, "initial " + ps[i].name);
            scene.parameters[i] = v.value;
            scene.parameters_written[i] = v;
            continue;
        }
        const double r = values.value(given, "initial " + rate).value;
        const double p = wheel_momentum_of(scene, ps[i].name.substr(2), r);
        if (!std::isfinite(p))
            throw user_error(location_of(given, file),
                             "the wheel's momentum from '" + rate + "' is not finite");
        scene.parameters[i] = p;
        scene.parameters_written[i] = written_value{p, GiNaC::ex(), false};
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
