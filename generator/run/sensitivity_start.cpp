#include "run/sensitivity_start.hpp"

#include "expr/numbers.hpp"
#include "expr/symbols.hpp"
#include "run/angle_chart.hpp"
#include "run/engine.hpp"

#include <cstdio>
#include <utility>

namespace rotgen {

namespace {

using GiNaC::ex;
using direction = std::vector<std::pair<ex, double>>; // (symbol, its derivative by the key)

ex number_of(long double x) {
    char text[64];
    std::snprintf(text, sizeof text, "%.21Le", x);
    return GiNaC::numeric(text);
}

// The derivative of e along `dir` at the point `at`: sum of d e/d x * dx.
double along(const ex& e, const GiNaC::exmap& at, const direction& dir) {
    long double sum = 0;
    for (const auto& [x, dx] : dir)
        if (dx != 0)
            sum +=
                dx * to_long_double(GiNaC::evalf(e.diff(GiNaC::ex_to<GiNaC::symbol>(x))
                                                     .subs(at, GiNaC::subs_options::no_pattern)));
    return static_cast<double>(sum);
}

// The derivative of the quaternion q_a(a0) (x) q_b(a1) (x) q_c(a2) (= q, w >= 0) by dq.
Eigen::Vector4d quaternion_derivative(const euler_sequence& s, const initial_kinematics& k,
                                      const std::array<double, 3>& dq) {
    using quat = Eigen::Quaterniond;
    const quat q(static_cast<double>(k.quat.w()), static_cast<double>(k.quat.x()),
                 static_cast<double>(k.quat.y()), static_cast<double>(k.quat.z()));
    const auto axis = [&](int i) { // (0, e_axis)
        Eigen::Vector3d e = Eigen::Vector3d::Zero();
        e[s.axes[static_cast<std::size_t>(i)]] = 1;
        return quat(0, e.x(), e.y(), e.z());
    };
    const double a0 = static_cast<double>(k.q[0]);
    const Eigen::Vector3d e0 = axis(0).vec();
    const quat qa(std::cos(a0 / 2), std::sin(a0 / 2) * e0.x(), std::sin(a0 / 2) * e0.y(),
                  std::sin(a0 / 2) * e0.z());
    const quat d0 = axis(0) * q;                       // 2 dq/da0
    const quat d1 = qa * axis(1) * qa.conjugate() * q; // 2 dq/da1
    const quat d2 = q * axis(2);                       // 2 dq/da2
    Eigen::Vector4d d = Eigen::Vector4d::Zero();
    for (const auto& [di, w] : {std::pair{d0, dq[0]}, {d1, dq[1]}, {d2, dq[2]}})
        d += 0.5 * w * Eigen::Vector4d(di.w(), di.x(), di.y(), di.z());
    return d;
}

// The derivatives of the initial kinematics by one key.
struct kinematics_derivative {
    std::array<double, 3> dq{}, dqd{}, dp{}, domega{};
    Eigen::Vector4d dquat = Eigen::Vector4d::Zero();
    std::vector<double> dparameters; // the model's
};

class start_differentiator {
  public:
    start_differentiator(const scene_spec& scene, const derivation& d, const member_values& values,
                         const initial_kinematics& k0)
        : m_scene(scene), m_d(d), m_k(k0) {
        const auto& s = symbols();
        const model_spec& spec = scene.model;
        for (std::size_t i = 0; i < spec.parameters.size(); ++i)
            m_at[spec.parameters[i].symbol] =
                exact_scene_value(values.parameters[i], i < scene.parameters_written.size()
                                                            ? scene.parameters_written[i]
                                                            : written_value{});
        for (std::size_t i = 0; i < 3; ++i) {
            m_at[s.q[i]] = exact_scene_value(values.angles[i], scene.angles_written[i]);
            m_at[s.qd[i]] = number_of(k0.qd[i]);
            m_at[s.omega[i]] = exact_scene_value(values.initial_rates[i], scene.rates_written[i]);
        }
    }

    kinematics_derivative by(const value_key& key) const;

  private:
    const scene_spec& m_scene;
    const derivation& m_d;
    const initial_kinematics& m_k;
    GiNaC::exmap m_at;
};

kinematics_derivative start_differentiator::by(const value_key& key) const {
    const auto& s = symbols();
    kinematics_derivative r;
    r.dparameters.assign(m_scene.model.parameters.size(), 0);
    std::array<double, 3> dr{}; // the initial rates as the scene gives them
    if (key.target == value_key::angle) r.dq[key.index] = 1;
    if (key.target == value_key::rate) dr[key.index] = 1;
    if (key.target == value_key::parameter) r.dparameters[key.index] = 1;
    direction base;
    for (std::size_t i = 0; i < 3; ++i)
        base.emplace_back(s.q[i], r.dq[i]);
    for (std::size_t i = 0; i < r.dparameters.size(); ++i)
        base.emplace_back(m_scene.model.parameters[i].symbol, r.dparameters[i]);
    r.dquat = quaternion_derivative(sequence_of(m_scene.model.angles), m_k, r.dq);
    if (m_scene.initial == initial_kind::omega) r.domega = dr;
    if (!m_k.have_rates) return r;
    if (m_scene.initial == initial_kind::rates) r.dqd = dr;
    if (m_scene.initial == initial_kind::omega) {
        direction with_omega = base;
        for (std::size_t j = 0; j < 3; ++j)
            with_omega.emplace_back(s.omega[j], dr[j]);
        for (std::size_t i = 0; i < 3; ++i) {
            ex qd = 0; // q_dot = J^{-1} omega (5.30)
            for (std::size_t j = 0; j < 3; ++j)
                qd += m_d.inverse_omega_jacobian[i][j] * s.omega[j];
            r.dqd[i] = along(qd, m_at, with_omega);
        }
    }
    if (m_scene.initial == initial_kind::momenta) { // M d q_dot = d p - dM q_dot
        Eigen::Matrix3d M;
        Eigen::Vector3d rhs;
        for (std::size_t i = 0; i < 3; ++i) {
            rhs[static_cast<Eigen::Index>(i)] = dr[i];
            for (std::size_t j = 0; j < 3; ++j) {
                const ex& m = m_d.mass_matrix[i][j];
                M(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = static_cast<double>(
                    to_long_double(GiNaC::evalf(m.subs(m_at, GiNaC::subs_options::no_pattern))));
                rhs[static_cast<Eigen::Index>(i)] -=
                    along(m, m_at, base) * static_cast<double>(m_k.qd[j]);
            }
        }
        const Eigen::Vector3d dqd = M.fullPivLu().solve(rhs);
        for (std::size_t i = 0; i < 3; ++i)
            r.dqd[i] = dqd[static_cast<Eigen::Index>(i)];
    }
    direction full = base;
    for (std::size_t i = 0; i < 3; ++i)
        full.emplace_back(s.qd[i], r.dqd[i]);
    for (std::size_t i = 0; i < 3; ++i) {
        r.dp[i] = along(m_d.momenta[i], m_at, full);
        if (m_scene.initial != initial_kind::omega) r.domega[i] = along(m_d.omega[i], m_at, full);
    }
    return r;
}

// The derivative of the state variable `name` (run/kinematics.cpp: state_value).
double state_derivative(const kinematics_derivative& r, const angle_convention& c,
                        const std::string& name) {
    for (std::size_t i = 0; i < 3; ++i) {
        const std::string& q = c.names[i];
        if (name == q) return r.dq[i];
        if (name == q + "_dot") return r.dqd[i];
        if (name == "p_" + q) return r.dp[i];
        if (name == "omega" + std::to_string(i + 1)) return r.domega[i];
    }
    const std::array<std::string, 4> quaternion{"qw", "qx", "qy", "qz"};
    for (int i = 0; i < 4; ++i)
        if (name == quaternion[static_cast<std::size_t>(i)]) return r.dquat[i];
    throw std::logic_error("unknown state variable " + name);
}

// The derivative of the form parameter `name`: a model parameter, or a cyclic momentum.
double parameter_derivative(const kinematics_derivative& r, const model_spec& spec,
                            const std::string& name) {
    for (std::size_t i = 0; i < spec.parameters.size(); ++i)
        if (spec.parameters[i].name == name) return r.dparameters[i];
    for (std::size_t i = 0; i < 3; ++i)
        if (name == "p_" + spec.angles.names[i]) return r.dp[i];
    throw std::logic_error("no value for the form parameter " + name);
}

} // namespace

std::vector<std::string> sensitivity_key_names(const scene_spec& scene, const form_expressions& f) {
    std::vector<std::string> names;
    for (const value_key& k : scene.sensitivities.keys)
        names.push_back(k.key);
    if (scene.sensitivities.all_initial)
        for (const auto& s : f.state)
            names.push_back("y0." + s.name);
    return names;
}

start_derivatives start_derivatives_of(const scene_spec& scene, const derivation& d,
                                       const form_expressions& f, const member_values& values,
                                       const initial_kinematics& k0) {
    const auto n = static_cast<Eigen::Index>(f.state.size()),
               np = static_cast<Eigen::Index>(f.parameters.size());
    start_derivatives r;
    if (scene.sensitivities.all_initial) {
        r.dy0 = Eigen::MatrixXd::Identity(n, n);
        r.dP = Eigen::MatrixXd::Zero(np, n);
        return r;
    }
    const auto k = static_cast<Eigen::Index>(scene.sensitivities.keys.size());
    r.dy0.resize(n, k);
    r.dP.resize(np, k);
    const scoped_digits digits(30);
    const start_differentiator differentiate(scene, d, values, k0);
    for (Eigen::Index j = 0; j < k; ++j) {
        const kinematics_derivative dk =
            differentiate.by(scene.sensitivities.keys[static_cast<std::size_t>(j)]);
        for (Eigen::Index i = 0; i < n; ++i) {
            const std::string& name = f.state[static_cast<std::size_t>(i)].name;
            bool wheel = false; // a torque-driven wheel's p starts at its parameter's value
            for (const parameter& p : scene.model.parameters)
                wheel = wheel || (p.wheel_state && p.name == name);
            r.dy0(i, j) = wheel ? parameter_derivative(dk, scene.model, name)
                                : state_derivative(dk, scene.model.angles, name);
        }
        for (Eigen::Index i = 0; i < np; ++i)
            r.dP(i, j) = parameter_derivative(dk, scene.model,
                                              f.parameters[static_cast<std::size_t>(i)].name);
    }
    return r;
}

} // namespace rotgen
