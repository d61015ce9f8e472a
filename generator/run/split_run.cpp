#include "run/split_run.hpp"

#include "expr/symbols.hpp"
#include "inertia/inertia.hpp"
#include "support/error.hpp"

#include <steppers/split_doubling.hpp>
#include <steppers/splitting.hpp>

#include <algorithm>

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
    if (!spec.wheels.empty())
        throw user_error(scene.integrator_where,
                         head +
                             "it carries wheels (a gyrostat), and the split methods' exact "
                             "free flow is the bare body's; use " +
                             other_methods);
    bool rates = spec.has_damping;
    for (const auto& c : spec.torque)
        rates = rates || depends_on_rates(c);
    if (rates)
        throw user_error(scene.integrator_where,
                         head + "its " + (spec.has_damping ? "damping" : "torque") +
                             " depends on the rates, which a kick cannot hold; use " +
                             other_methods);
    const std::array<double, 3> moments = split_frame(inertia).moments;
    if (!(*std::min_element(moments.begin(), moments.end()) > 0))
        throw user_error(scene.integrator_where,
                         head + "a principal moment is not positive (a rotor); use " +
                             other_methods);
}

split_frame_values split_frame(const Eigen::Matrix3d& inertia) {
    split_frame_values f;
    const Eigen::Matrix3d off = inertia - Eigen::Matrix3d(inertia.diagonal().asDiagonal());
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            f.tensor[i][j] = inertia(i, j);
    f.principal = off.cwiseAbs().maxCoeff() > 0;
    if (!f.principal) {
        f.moments = {inertia(0, 0), inertia(1, 1), inertia(2, 2)};
        return f;
    }
    // the principal axes of the inertia stage (rows of A = Pᵀ, (5.69)), proper
    const principal_axes pa = numeric_principal_axes(f.tensor);
    f.moments = pa.moment_values;
    Eigen::Matrix3d p;
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
            p(j, k) = pa.axis_values[k][j];
    const Eigen::Quaterniond q(p);
    f.axes = {q.w(), q.x(), q.y(), q.z()};
    return f;
}

split_runner::split_runner(const scene_spec& scene, const Eigen::Matrix3d& inertia)
    : m_method(scene.integrator.method), m_order(m_method.back() - '0'),
      m_rtol(scene.integrator.rtol), m_atol(scene.integrator.atol), m_step(scene.integrator.step),
      m_max_steps(static_cast<std::size_t>(scene.integrator.max_steps)),
      m_frame(split_frame(inertia)) {}

body_split_system<loaded_system> split_runner::system(const loaded_system& body) const {
    if (!m_frame.principal) return body_split_system<loaded_system>(body, m_frame.moments);
    return body_split_system<loaded_system>(body, m_frame.tensor, m_frame.moments, m_frame.axes);
}

integration_result<double> split_runner::integrate(const loaded_system& body, double t0,
                                                   Eigen::VectorXd& y,
                                                   const std::vector<double>& times,
                                                   const observer& observe,
                                                   event_set<double, Eigen::VectorXd>* events,
                                                   const error_layout& layout) const {
    const body_split_system<loaded_system> sys = system(body);
    const auto run = [&](auto method) {
        method.max_steps = m_max_steps;
        return events ? rotgen::integrate(sys, method, t0, y, times, observe, *events)
                      : rotgen::integrate(sys, method, t0, y, times, observe);
    };
    const auto fixed_or_controlled = [&](auto fixed, auto controlled) {
        if (m_step > 0) {
            fixed.step = m_step;
            return run(fixed);
        }
        controlled.rtol = m_rtol;
        controlled.atol = m_atol;
        calibrate(controlled, layout);
        return run(controlled);
    };
    if (m_order == 2) return fixed_or_controlled(split2<double>(), split2_controlled<double>());
    if (m_order == 4) return fixed_or_controlled(split4<double>(), split4_controlled<double>());
    return fixed_or_controlled(split6<double>(), split6_controlled<double>());
}

} // namespace rotgen
