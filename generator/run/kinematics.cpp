#include "run/kinematics.hpp"

#include "emit/emit.hpp" // exact_decimal
#include "expr/numbers.hpp"
#include "expr/symbols.hpp"
#include "inertia/inertia.hpp"
#include "support/error.hpp"
#include "support/format.hpp"

#include "run/angle_chart.hpp"
#include "run/rotor_chart.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

namespace rotgen {

GiNaC::ex exact_scene_value(double current, const written_value& written) {
    if (written.expression && written.value == current) return written.exact;
    return exact_decimal(current);
}

namespace {

using GiNaC::ex;

ex written_at(const std::vector<written_value>& w, std::size_t i, double current) {
    return exact_scene_value(current, i < w.size() ? w[i] : written_value{});
}

// q_dot = M(q)^{-1} p, solved in long double.
std::array<ex, 3> rates_from_momenta(const scene_spec& scene, const derivation& d,
                                     const GiNaC::exmap& at) {
    Eigen::Matrix<long double, 3, 3> M;
    Eigen::Matrix<long double, 3, 1> p;
    for (int i = 0; i < 3; ++i) {
        p[i] = to_long_double(exact_scene_value(scene.initial_rates[i], scene.rates_written[i]));
        for (int j = 0; j < 3; ++j)
            M(i, j) = to_long_double(d.mass_matrix[i][j].subs(at, GiNaC::subs_options::no_pattern));
    }
    const std::array<std::string, 3> text = rates_text(M, p);
    std::array<ex, 3> qd;
    for (std::size_t i = 0; i < 3; ++i)
        qd[i] = GiNaC::numeric(text[i].c_str());
    return qd;
}

// q_dot = J^{-1} omega (5.30).
std::array<ex, 3> rates_from_omega(const scene_spec& scene, const derivation& d,
                                   const GiNaC::exmap& at) {
    std::array<ex, 3> qd;
    for (int i = 0; i < 3; ++i) {
        ex r = 0;
        for (int j = 0; j < 3; ++j)
            r += d.inverse_omega_jacobian[i][j] *
                 exact_scene_value(scene.initial_rates[j], scene.rates_written[j]);
        qd[i] = r.subs(at, GiNaC::subs_options::no_pattern);
    }
    return qd;
}

} // namespace

std::array<std::string, 3> rates_text(const Eigen::Matrix<long double, 3, 3>& M,
                                      const Eigen::Matrix<long double, 3, 1>& p) {
    const Eigen::Matrix<long double, 3, 1> v = M.fullPivLu().solve(p);
    std::array<std::string, 3> text;
    for (int i = 0; i < 3; ++i) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.21Le", v[i]);
        text[static_cast<std::size_t>(i)] = buf;
    }
    return text;
}

initial_kinematics initial_kinematics_of(const scene_spec& scene, const derivation& d) {
    const auto& s = symbols();
    const scoped_digits digits(30);
    initial_kinematics k;
    GiNaC::exmap at;
    for (std::size_t i = 0; i < scene.model.parameters.size(); ++i)
        at[scene.model.parameters[i].symbol] =
            written_at(scene.parameters_written, i, scene.parameters[i]);
    for (int i = 0; i < 3; ++i) {
        at[s.q[i]] = exact_scene_value(scene.angles[i], scene.angles_written[i]);
        k.q[i] = to_long_double(at[s.q[i]]);
    }
    at[s.t] = GiNaC::numeric(scene.t_start); // a wheel's rate drive: p depends on t
    const euler_sequence sequence = sequence_of(scene.model.angles);
    k.have_rates = chart_distance(sequence, scene.angles[1]) >= 1e-12;
    std::array<ex, 3> qd;
    if (scene.initial == initial_kind::rates)
        for (int i = 0; i < 3; ++i)
            qd[i] = exact_scene_value(scene.initial_rates[i], scene.rates_written[i]);
    else if (k.have_rates)
        qd = scene.initial == initial_kind::momenta ? rates_from_momenta(scene, d, at)
                                                    : rates_from_omega(scene, d, at);
    if (scene.initial == initial_kind::rates) k.have_rates = true;
    if (k.have_rates) {
        for (int i = 0; i < 3; ++i)
            at[s.qd[i]] = qd[i];
        for (int i = 0; i < 3; ++i) {
            k.qd[i] = to_long_double(qd[i]);
            k.p[i] = to_long_double(d.momenta[i].subs(at, GiNaC::subs_options::no_pattern));
            k.omega[i] = to_long_double(d.omega[i].subs(at, GiNaC::subs_options::no_pattern));
        }
    }
    if (scene.initial == initial_kind::omega)
        for (int i = 0; i < 3; ++i)
            k.omega[i] =
                to_long_double(exact_scene_value(scene.initial_rates[i], scene.rates_written[i]));
    k.quat = quaternion_of_angles<long double>(sequence, k.q[0], k.q[1], k.q[2]);
    return k;
}

void check_double_range(const scene_spec& scene, const initial_kinematics& k) {
    const long double big = std::numeric_limits<double>::max();
    const auto check = [&](const std::string& what, long double v) {
        if (std::isfinite(v) && std::abs(v) <= big) return;
        throw user_error(
            scene.initial_where,
            "initial values too large for double precision: " + what + " = " +
                short_wide_number(v) +
                "; give smaller initial rates or momenta, or rescale the model's units");
    };
    const auto& q = scene.model.angles.names;
    long double twice_kinetic = 0;
    for (std::size_t i = 0; i < 3; ++i) {
        check("omega" + std::to_string(i + 1), k.omega[i]);
        if (!k.have_rates) continue;
        check(q[i] + "_dot", k.qd[i]);
        check("p_" + q[i], k.p[i]);
        twice_kinetic += k.p[i] * k.qd[i];
    }
    check("the kinetic energy", twice_kinetic / 2);
}

// The scene's own parameter values were checked when it was read (scene/scene.cpp); a sweep
// member's may still make the tensor unphysical: such a member is rejected, with the reason.
void check_physical_inertia(const scene_spec& scene, const Eigen::Matrix3d& inertia) {
    const Eigen::Vector3d m = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
    std::string problem = negative_moment_problem({m[0], m[1], m[2]});
    if (problem.empty()) problem = triangle_problem({m[0], m[1], m[2]});
    if (problem.empty() && !scene.model.rotor && !(m[0] > 1e-14 * m.cwiseAbs().maxCoeff()))
        problem = "a principal moment is zero (" + short_number(m[0]) + ", " + short_number(m[1]) +
                  ", " + short_number(m[2]) + "): the mass matrix is singular";
    if (!problem.empty())
        throw user_error(scene.where, "rejected: with these parameter values the inertia is not "
                                      "physical: " +
                                          problem);
}

long double scene_parameter_value(const scene_spec& scene, const initial_kinematics& k,
                                  const std::string& name) {
    const model_spec& spec = scene.model;
    for (std::size_t i = 0; i < spec.parameters.size(); ++i)
        if (spec.parameters[i].name == name) {
            const scoped_digits digits(30);
            return to_long_double(written_at(scene.parameters_written, i, scene.parameters[i]));
        }
    for (int i = 0; i < 3; ++i)
        if (name == "p_" + spec.angles.names[i]) {
            // Unreachable from a scene: the reduced form never starts at |sin theta| < 1e-10
            // (run/engine.cpp decide_chart and bench's prepare refuse it; bench adds reduced
            // alternatives only with rates), so the momenta are always known here.
            if (!k.have_rates)
                throw std::logic_error("run: the reduced form's momenta are unknown at theta = 0");
            return k.p[static_cast<std::size_t>(i)];
        }
    throw std::logic_error("no value for the form parameter " + name);
}

long double state_value(const initial_kinematics& k, const angle_convention& c,
                        const std::string& name) {
    for (int i = 0; i < 3; ++i) {
        const std::string& q = c.names[i];
        const auto u = static_cast<std::size_t>(i);
        if (name == q) return k.q[u];
        if (name == q + "_dot") return k.qd[u];
        if (name == "p_" + q) return k.p[u];
        if (name == "omega" + std::to_string(i + 1)) return k.omega[u];
    }
    for (const auto& [wheel, value] : k.wheels)
        if (name == wheel) return value;
    if (name == "qw") return k.quat.w();
    if (name == "qx") return k.quat.x();
    if (name == "qy") return k.quat.y();
    if (name == "qz") return k.quat.z();
    throw std::logic_error("unknown state variable " + name);
}

std::vector<double> form_parameter_values(const scene_spec& scene,
                                          const std::vector<long double>& model_values,
                                          const std::vector<form_parameter>& parameters,
                                          const initial_kinematics& k) {
    std::vector<double> values;
    const model_spec& spec = scene.model;
    for (const auto& fp : parameters) {
        std::optional<long double> v;
        for (std::size_t i = 0; i < spec.parameters.size() && !v; ++i)
            if (spec.parameters[i].name == fp.name) v = model_values[i];
        for (int i = 0; i < 3 && !v; ++i)
            if (fp.name == "p_" + spec.angles.names[static_cast<std::size_t>(i)]) {
                if (!k.have_rates)
                    throw user_error(scene.initial_where,
                                     "the reduced form needs the initial momenta");
                v = k.p[static_cast<std::size_t>(i)];
            }
        if (!v) throw std::logic_error("no value for the form parameter " + fp.name);
        values.push_back(static_cast<double>(*v));
    }
    return values;
}

Eigen::VectorXd form_state(const form_expressions& f, const initial_kinematics& k,
                           const angle_convention& c, form_kind scene_form) {
    if (is_rotor_form(f.form)) return rotor_state(f.form, k);
    Eigen::VectorXd y(static_cast<Eigen::Index>(f.state.size()));
    for (std::size_t s = 0; s < f.state.size(); ++s) {
        const std::string& name = f.state[s].name;
        bool needs_rates = name.find("_dot") != std::string::npos || name.rfind("p_", 0) == 0;
        for (const auto& w : k.wheels)
            needs_rates = needs_rates && w.first != name;
        // Unreachable from a scene: without rates (|sin theta| < 1e-12) an Euler-angle form
        // either starts in the body form (decide_chart: the switch below 0.1) or is refused by
        // decide_chart (|sin theta| < 1e-10 without the switch), and a switch back to it happens
        // only above |sin theta| = 0.3.
        if (needs_rates && !k.have_rates)
            throw std::logic_error("run: the " + std::string(to_string(scene_form)) +
                                   " form was started at the singularity from body omega");
        y[static_cast<Eigen::Index>(s)] = static_cast<double>(state_value(k, c, name));
    }
    return y;
}

} // namespace rotgen
