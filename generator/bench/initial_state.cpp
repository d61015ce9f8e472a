// rotgen bench: the initial state in long double, and the check that double can hold it.
#include "bench/initial_state.hpp"

#include "bench/numbers.hpp"
#include "emit/emit.hpp" // exact_decimal
#include "expr/symbols.hpp"
#include "support/error.hpp"

#include <rotation.hpp> // runtime: quaternion_from_euler

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

namespace rotgen::bench {

namespace {

using GiNaC::ex;
using rates = std::array<ex, 3>;

// M q_dot = p, solved in long double (M and p evaluated at `at`: parameters and angles).
rates rates_from_momenta(const scene_spec& scene, const derivation& d, const GiNaC::exmap& at) {
    Eigen::Matrix<long double, 3, 3> M;
    Eigen::Matrix<long double, 3, 1> p;
    for (int i = 0; i < 3; ++i) {
        p[i] = to_long_double(exact_decimal(scene.initial_rates[i]));
        for (int j = 0; j < 3; ++j)
            M(i, j) = to_long_double(d.mass_matrix[i][j].subs(at));
    }
    const Eigen::Matrix<long double, 3, 1> v = M.fullPivLu().solve(p);
    rates qd;
    for (int i = 0; i < 3; ++i) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.21Le", v[i]);
        qd[i] = GiNaC::numeric(buf);
    }
    return qd;
}

// q_dot = J^{-1} omega (5.30), exactly.
rates rates_from_omega(const scene_spec& scene, const derivation& d, const GiNaC::exmap& at) {
    rates qd;
    for (int i = 0; i < 3; ++i) {
        ex r = 0;
        for (int j = 0; j < 3; ++j)
            r += d.inverse_omega_jacobian[i][j] * exact_decimal(scene.initial_rates[j]);
        qd[i] = r.subs(at);
    }
    return qd;
}

// The initial q_dot; none from momenta or omega at sin theta = 0, where J and M are singular.
std::optional<rates> initial_rates(const scene_spec& scene, const derivation& d,
                                   const GiNaC::exmap& at) {
    const bool singular = std::abs(std::sin(scene.angles[1])) < 1e-12;
    switch (scene.initial) {
    case initial_kind::rates: {
        rates qd;
        for (int i = 0; i < 3; ++i)
            qd[i] = exact_decimal(scene.initial_rates[i]);
        return qd;
    }
    case initial_kind::momenta:
        if (singular) return std::nullopt;
        return rates_from_momenta(scene, d, at);
    case initial_kind::omega:
        if (singular) return std::nullopt;
        return rates_from_omega(scene, d, at);
    }
    return rates{};
}

} // namespace

// shared with simulate: to be replaced by run/'s one initial-kinematics function
kinematics initial_kinematics(const scene_spec& scene, const derivation& d,
                              const GiNaC::exmap& parameters) {
    const auto& s = symbols();
    const scoped_digits digits(30);
    kinematics k;
    GiNaC::exmap at = parameters;
    for (int i = 0; i < 3; ++i) {
        at[s.q[i]] = exact_decimal(scene.angles[i]);
        k.q[i] = to_long_double(exact_decimal(scene.angles[i]));
    }
    const std::optional<rates> qd = initial_rates(scene, d, at);
    k.have_rates = qd.has_value();
    if (qd) {
        for (int i = 0; i < 3; ++i)
            at[s.qd[i]] = (*qd)[i];
        for (int i = 0; i < 3; ++i) {
            k.qd[i] = to_long_double((*qd)[i]);
            k.p[i] = to_long_double(d.momenta[i].subs(at));   // p = dL/dq_dot
            k.omega[i] = to_long_double(d.omega[i].subs(at)); // (5.30)
        }
    }
    if (scene.initial == initial_kind::omega)
        for (int i = 0; i < 3; ++i)
            k.omega[i] = to_long_double(exact_decimal(scene.initial_rates[i]));
    k.quat = quaternion_from_euler<long double>(k.q[0], k.q[1], k.q[2]);
    return k;
}

// shared with simulate: to be replaced by run/'s overflow check
void check_double_range(const scene_spec& scene, const kinematics& k) {
    const long double big = std::numeric_limits<double>::max();
    const auto check = [&](const std::string& what, long double v) {
        if (std::isfinite(v) && std::abs(v) <= big) return;
        throw user_error(
            scene.initial_where,
            "initial values too large for double precision: " + what + " = " +
                std::to_string(static_cast<double>(v)) +
                "; give smaller initial rates or momenta, or rescale the model's units");
    };
    const std::array<const char*, 3> q{"phi", "theta", "psi"};
    long double twice_kinetic = 0;
    for (std::size_t i = 0; i < 3; ++i) {
        check("omega" + std::to_string(i + 1), k.omega[i]);
        if (!k.have_rates) continue;
        check(std::string(q[i]) + "_dot", k.qd[i]);
        check(std::string("p_") + q[i], k.p[i]);
        twice_kinetic += k.p[i] * k.qd[i];
    }
    check("the kinetic energy", twice_kinetic / 2);
}

} // namespace rotgen::bench
