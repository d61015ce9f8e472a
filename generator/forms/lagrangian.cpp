// rotgen — forms/: the Lagrangian form, y = (phi, theta, psi, phi_dot, theta_dot, psi_dot),
// M(q) q_ddot = f(t, q, q_dot) with M = J^T I J, J = d omega / d q_dot of (5.30).
//
// Strategy `explicit`: q_ddot = J^{-1} I^{-1} J^{-T} f, with two alternatives by other routes
// (M^{-1} in canonical form times f; Euler's equations and J^{-1}); the emitter keeps whichever
// lowers to the fewest operations. Strategy `solve`: M and f kept apart and solved by an inline L D
// L^T.
#include "forms/form_algebra.hpp"

#include "expr/angles.hpp"
#include "expr/symbols.hpp"

namespace rotgen::form_detail {

using GiNaC::ex;

namespace {

// q_ddot = M^{-1} f with M^{-1} itself in canonical form (identities such as sin^2 + cos^2 of psi
// cancel there): M^{-1}_ij = sum_kl J^{-1}_ik I^{-1}_kl J^{-1}_jl.
vec inverse_mass_times_forcing(const derivation& d) {
    matrix3 minv;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            ex e = 0;
            for (int k = 0; k < 3; ++k)
                for (int l = 0; l < 3; ++l)
                    e += d.inverse_omega_jacobian[i][k] * d.inverse_inertia[k][l] *
                         d.inverse_omega_jacobian[j][l];
            minv[i][j] = canonical(e);
        }
    return mat_vec(minv, d.forcing);
}

// q_ddot by Euler's equations: omega_dot = I^{-1} (tau - omega x I omega), tau = J^{-T} Q_total
// (Q_total = -dV/dq + Q, in canonical form: for gravity the 1/sin(theta) cancels), and
// q_ddot = J^{-1} (omega_dot - J_dot q_dot), J_dot q_dot = sum_j d omega/d q_j q_dot_j.
vec euler_equations_q_ddot(const model_spec& spec, const derivation& d) {
    const auto& s = symbols();
    vec q_total;
    for (int i = 0; i < 3; ++i)
        q_total[i] = -d.potential.diff(s.q[i]) + d.generalized_force[i];
    vec tau = mat_t_vec(d.inverse_omega_jacobian, q_total);
    for (auto& t : tau)
        t = canonical(t);
    const vec Iw = mat_vec(spec.inertia, d.omega);
    const vec gyro = cross(d.omega, momentum_of(d, Iw)); // omega x (I omega + h)
    vec b;
    GiNaC::exmap omega_of_rates; // the motors' reaction (torque-driven wheels): -sum tau a
    for (int i = 0; i < 3; ++i)
        omega_of_rates[s.omega[i]] = d.omega[i];
    for (int i = 0; i < 3; ++i) {
        b[i] = d.wheels.driven ? tau[i] - gyro[i] - d.wheels.h_dot[i] : tau[i] - gyro[i];
        if (d.wheels.torqued) b[i] += d.wheels.motor[i].subs(omega_of_rates);
    }
    const vec wd = mat_vec(d.inverse_inertia, b);
    vec a;
    for (int i = 0; i < 3; ++i) {
        ex jdot = 0;
        for (int j = 0; j < 3; ++j)
            jdot += d.omega[i].diff(s.q[j]) * s.qd[j];
        a[i] = wd[i] - canonical(jdot);
    }
    return mat_vec(d.inverse_omega_jacobian, a);
}

void explicit_rates(const model_spec& spec, const derivation& d, form_expressions& f) {
    const auto& s = symbols();
    // q_ddot = M^{-1} f with M^{-1} = J^{-1} I^{-1} J^{-T}, applied right to left.
    const vec g = mat_t_vec(d.inverse_omega_jacobian, d.forcing);
    const vec h = mat_vec(d.inverse_inertia, g);
    const vec qdd = mat_vec(d.inverse_omega_jacobian, h);
    for (int i = 0; i < 3; ++i)
        f.rates.push_back(qdd[i]);
    const vec qdd2 = inverse_mass_times_forcing(d);
    f.alternative_rates.push_back({s.qd[0], s.qd[1], s.qd[2], qdd2[0], qdd2[1], qdd2[2]});
    const vec qdd3 = euler_equations_q_ddot(spec, d);
    f.alternative_rates.push_back({s.qd[0], s.qd[1], s.qd[2], qdd3[0], qdd3[1], qdd3[2]});
    f.notes.push_back(
        "q_ddot = J^{-1} I^{-1} J^{-T} f (M^{-1} = J^{-1} I^{-1} J^{-T}, M = J^T I J, "
        "J = d omega/d q_dot of (5.30)); " +
        f.angles.singular_clause() + ".");
}

void solve_rates(const derivation& d, form_expressions& f) {
    // M q_ddot = f by LDL^T, written out: the zeros of M drop out as the code is built.
    f.mass = d.mass_matrix;
    f.forcing = d.forcing;
    const vec qdd = ldlt_solve(ldlt_factor(f.mass), d.forcing);
    for (int i = 0; i < 3; ++i)
        f.rates.push_back(qdd[i]);
    f.notes.push_back(
        "M(q) q_ddot = f(t, q, q_dot) solved by an inline LDL^T (no pivoting; M = J^T I J "
        "is positive definite for " +
        f.angles.regular_range() + ", singular at " + f.angles.singular_text() + ").");
}

} // namespace

void build_lagrangian(const model_spec& spec, const derivation& d, form_expressions& f) {
    const auto& s = symbols();
    const auto& q_names = f.angles.names;
    for (int i = 0; i < 3; ++i)
        f.state.push_back({q_names[i], s.q[i], "Euler angle (z-x-z), rad"});
    for (int i = 0; i < 3; ++i)
        f.state.push_back({q_names[i] + "_dot", s.qd[i], "its rate, rad/time"});
    for (int i = 0; i < 3; ++i) {
        f.rates.push_back(s.qd[i]);
        f.rate_names.push_back(q_names[i] + "_dot");
    }
    if (f.strategy == lagrangian_strategy::explicit_inverse)
        explicit_rates(spec, d, f);
    else
        solve_rates(d, f);
    for (int i = 0; i < 3; ++i)
        f.rate_names.push_back(q_names[i] + "_ddot");
    GiNaC::exmap in_state; // a wheel's torque: omega = J q_dot
    for (int i = 0; i < 3; ++i)
        in_state[s.omega[i]] = d.omega[i];
    add_wheel_states(spec, f, [&](const ex& e) { return e.subs(in_state); });

    // omega = J q_dot (5.30); T = 1/2 omega . I omega (5.38); p = J^T I omega.
    const vec w = d.omega;
    const vec Iw = mat_vec(spec.inertia, w);
    add_output(f, "energy", {kinetic_of(d, w, Iw) + d.potential}, {"energy"});
    f.outputs["energy"].alternatives.push_back({d.energy});
    const vec p = mat_t_vec(d.omega_jacobian, momentum_of(d, Iw));
    add_output(f, "momenta", {p[0], p[1], p[2]}, momentum_names(f.angles));
    f.outputs["momenta"].alternatives.push_back({d.momenta[0], d.momenta[1], d.momenta[2]});
    add_output(f, "omega", {w[0], w[1], w[2]}, {"omega1", "omega2", "omega3"});
}

} // namespace rotgen::form_detail
