#include "run/split_run.hpp"

#include "expr/symbols.hpp"
#include "support/error.hpp"

#include <split_step_rule.hpp>
#include <steppers/splitting.hpp>

namespace rotgen {

namespace {

const char* other_methods = "dop853, dopri5, rk4, implicit_midpoint, rosenbrock or taylor";

bool depends_on_rates(const GiNaC::ex& e) {
    const coordinate_symbols& s = symbols();
    for (int i = 0; i < 3; ++i)
        if (e.has(s.qd[i]) || e.has(s.omega[i]) || e.has(s.p[i])) return true;
    return false;
}

} // namespace

bool is_split_method(const std::string& method) {
    return method == "split2" || method == "split4" || method == "split6";
}

void check_split_model(const scene_spec& scene, const Eigen::Matrix3d& inertia) {
    const model_spec& spec = scene.model;
    const std::string head =
        "integrator " + scene.integrator.method + " cannot run model '" + spec.name + "': ";
    if (!scene.events.empty())
        throw user_error(scene.integrator_where, "integrator " + scene.integrator.method +
                                                     " does not locate events yet; use " +
                                                     other_methods + " for a scene with events");
    bool rates = spec.has_damping;
    for (const auto& c : spec.torque)
        rates = rates || depends_on_rates(c);
    if (rates)
        throw user_error(scene.integrator_where,
                         head + "its " + (spec.has_damping ? "damping" : "torque") +
                             " depends on the rates, which a kick cannot hold; use " +
                             other_methods);
    const Eigen::Matrix3d off = inertia - Eigen::Matrix3d(inertia.diagonal().asDiagonal());
    if (off.cwiseAbs().maxCoeff() > 0)
        throw user_error(scene.integrator_where,
                         head +
                             "its body axes are not principal axes (the inertia has products "
                             "of inertia); give the principal moments, or use " +
                             other_methods);
    if (!(inertia.diagonal().minCoeff() > 0))
        throw user_error(scene.integrator_where,
                         head + "a principal moment is not positive (a rotor); use " +
                             other_methods);
}

split_runner::split_runner(const scene_spec& scene, const Eigen::Matrix3d& inertia)
    : m_method(scene.integrator.method), m_order(m_method.back() - '0'),
      m_rtol(scene.integrator.rtol), m_step(scene.integrator.step),
      m_max_steps(static_cast<std::size_t>(scene.integrator.max_steps)), m_moments{inertia(0, 0),
                                                                                   inertia(1, 1),
                                                                                   inertia(2, 2)} {}

void split_runner::choose_step(const loaded_system& body, double t0, const Eigen::VectorXd& y0,
                               double span) {
    if (m_step > 0) return;
    const body_split_system<loaded_system> sys(body, m_moments);
    m_step = split_step_for_tolerance(sys, m_order, m_rtol, t0, y0, span);
}

integration_result<double> split_runner::integrate(const loaded_system& body, double t0,
                                                   Eigen::VectorXd& y,
                                                   const std::vector<double>& times,
                                                   const observer& observe) const {
    const body_split_system<loaded_system> sys(body, m_moments);
    const auto run = [&](auto method) {
        method.step = m_step;
        method.max_steps = m_max_steps;
        return rotgen::integrate(sys, method, t0, y, times, observe);
    };
    if (m_order == 2) return run(split2<double>());
    if (m_order == 4) return run(split4<double>());
    return run(split6<double>());
}

} // namespace rotgen
