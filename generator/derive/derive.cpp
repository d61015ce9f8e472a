#include "derive/derive.hpp"

#include "expr/angles.hpp"
#include "expr/symbols.hpp"

namespace rotgen {

using GiNaC::ex;

ex canonical(const ex& e) {
    const auto& s = symbols();
    ex r = e.expand();
    for (int i : {0, 2}) {
        const ex sin2 = GiNaC::pow(GiNaC::sin(s.q[i]), 2);
        r = r.subs(sin2 == 1 - GiNaC::pow(GiNaC::cos(s.q[i]), 2), GiNaC::subs_options::algebraic)
                .expand();
    }
    return r;
}

ex time_derivative(const ex& e) {
    const auto& s = symbols();
    ex d = e.diff(s.t);
    for (int i = 0; i < 3; ++i)
        d += e.diff(s.q[i]) * s.qd[i] + e.diff(s.qd[i]) * s.qdd[i];
    return d;
}

namespace {

// (5.30) for z-x-z, any sequence a-b-c alike: omega = J(q) q_dot with J derived from the product
// of the elementary rotations (expr/angles.hpp), J = [A_c A_b e_a | A_c e_b | e_c]; for z-x-z
//   J = [[sin(theta) sin(psi),  cos(psi), 0],
//        [sin(theta) cos(psi), -sin(psi), 0],
//        [cos(theta),           0,        1]].
matrix3 omega_jacobian(const angle_convention& c) {
    return omega_jacobian_of(c);
}

// sin^2 -> 1 - cos^2 of the last angle (J does not depend on the first), then expanded: what
// collapses J's cofactors.
ex trig_collapse(const ex& e) {
    const ex gamma = symbols().q[2];
    const ex sin2 = GiNaC::pow(GiNaC::sin(gamma), 2);
    return e.expand()
        .subs(sin2 == 1 - GiNaC::pow(GiNaC::cos(gamma), 2), GiNaC::subs_options::algebraic)
        .expand();
}

// J^{-1} = adj(J) / det J by cofactors. det J is one term: -sin(theta) for z-x-z (so that
// phi_dot = (omega1 sin psi + omega2 cos psi) / sin theta, theta_dot = omega1 cos psi - omega2
// sin psi, psi_dot = omega3 - phi_dot cos theta), +-sin(beta) for a proper Euler sequence and
// +-cos(beta) for a Tait-Bryan one: the singular set.
matrix3 inverse_omega_jacobian(const matrix3& J) {
    matrix3 adj, inv;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            adj[i][j] = trig_collapse(J[r0][c0] * J[r1][c1] - J[r0][c1] * J[r1][c0]);
        }
    ex det = 0;
    for (int k = 0; k < 3; ++k)
        det += J[0][k] * adj[k][0];
    det = trig_collapse(det);
    if (GiNaC::is_a<GiNaC::add>(det))
        throw std::logic_error("derive: det J did not collapse to one term");
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            inv[i][j] = trig_collapse(adj[i][j] / det);
    return inv;
}

// I^{-1} by the adjugate: small and exact for a symbolic tensor; 1/I_ii when diagonal.
matrix3 inverse_inertia(const model_spec& spec) {
    const matrix3& I = spec.inertia;
    matrix3 inv;
    if (spec.inertia_diagonal) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                inv[i][j] = i == j ? 1 / I[i][i] : ex(0);
        return inv;
    }
    matrix3 adj;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            // adj[i][j] = cofactor of I[j][i]
            const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            adj[i][j] = (I[r0][c0] * I[r1][c1] - I[r0][c1] * I[r1][c0]).expand();
        }
    ex det = 0;
    for (int k = 0; k < 3; ++k)
        det += I[0][k] * adj[k][0];
    det = det.expand();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            inv[i][j] = adj[i][j] / det;
    return inv;
}

// A linear rotor has two angles, not three: its mass matrix in (phi, theta, psi) is singular.
void refuse_rotor(const model_spec& spec) {
    if (spec.rotor)
        throw user_error(spec.rotor_where,
                         "model '" + spec.name +
                             "' is a linear rotor (I1 = 0, I2 = I3: a body on a line, Example "
                             "5.4); its motion has two angles (phi, theta): emit and simulate "
                             "run it in the rotor form, and this command takes three-angle "
                             "tops only; 'rotgen inspect " +
                             spec.file + "' prints its equations");
}

// J^T tau for a body-axis torque tau that may use omega, which is J q_dot here (5.30): the
// virtual work tau . J dq.
vector3 torque_force(const derivation& d, const vector3& tau) {
    const auto& s = symbols();
    GiNaC::exmap omega_of_rates;
    for (int i = 0; i < 3; ++i)
        omega_of_rates[s.omega[i]] = d.omega[i];
    vector3 Q;
    for (int i = 0; i < 3; ++i) {
        Q[i] = 0;
        for (int k = 0; k < 3; ++k)
            Q[i] += d.omega_jacobian[k][i] * tau[k].subs(omega_of_rates);
    }
    return Q;
}

// Q = -c q_dot + J^T tau (body damping -c_i omega_i may be in tau).
vector3 generalized_force(const model_spec& spec, const derivation& d) {
    const vector3 torque = torque_force(d, spec.torque);
    vector3 Q;
    for (int i = 0; i < 3; ++i)
        Q[i] = canonical(-spec.damping[i] * symbols().qd[i] + torque[i]);
    return Q;
}

// The motors' reaction on the body as a generalised force, J^T motor (motor = -sum tau_k a_k).
// The Lagrangian forcing only: wheels.hpp.
vector3 motor_force(const derivation& d) {
    vector3 Q = torque_force(d, d.wheels.motor);
    for (auto& q : Q)
        q = canonical(q);
    return Q;
}

// l = J^{-T} p; H = 1/2 l^T I^{-1} l + V (with wheels (l - h) for l, and - routh: wheels.hpp);
// Hamilton's equations q_dot = dH/dp, p_dot = -dH/dq + Q(q, dH/dp).
void hamiltonian_side(derivation& d) {
    const auto& s = symbols();
    const wheel_terms& wh = d.wheels;
    for (int i = 0; i < 3; ++i) {
        ex l = 0;
        for (int j = 0; j < 3; ++j)
            l += d.inverse_omega_jacobian[j][i] * s.p[j];
        d.body_momentum[i] = canonical(l);
    }
    vector3 lb = d.body_momentum;
    if (wh.any)
        for (int i = 0; i < 3; ++i)
            lb[i] = canonical(lb[i] - wh.h[i]);
    ex H = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            H += lb[i] * d.inverse_inertia[i][j] * lb[j];
    d.hamiltonian =
        wh.any ? canonical(H / 2 - wh.routh + d.potential) : canonical(H / 2 + d.potential);

    GiNaC::exmap rates_of_p;
    for (int i = 0; i < 3; ++i) {
        d.hamilton_qdot[i] = canonical(d.hamiltonian.diff(s.p[i]));
        rates_of_p[s.qd[i]] = d.hamilton_qdot[i];
    }
    for (int i = 0; i < 3; ++i)
        d.hamilton_pdot[i] =
            canonical(-d.hamiltonian.diff(s.q[i]) + d.generalized_force[i].subs(rates_of_p));
}

} // namespace

derivation derive(const model_spec& model) {
    refuse_rotor(model);
    const model_spec spec = gyrostat_body(model);
    const auto& s = symbols();
    derivation d;
    d.wheels = wheel_terms_of(model);
    const wheel_terms& wh = d.wheels;
    d.angles = spec.angles;
    d.omega_jacobian = omega_jacobian(spec.angles);
    d.inverse_omega_jacobian = inverse_omega_jacobian(d.omega_jacobian);
    d.inverse_inertia = inverse_inertia(spec);

    // omega = J q_dot (5.30)
    for (int i = 0; i < 3; ++i) {
        ex w = 0;
        for (int j = 0; j < 3; ++j)
            w += d.omega_jacobian[i][j] * s.qd[j];
        d.omega[i] = canonical(w);
    }
    // T = 1/2 omega^T I omega (5.38)
    ex T = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            T += spec.inertia[i][j] * d.omega[i] * d.omega[j];
    d.kinetic = canonical(T / 2);
    d.potential = canonical(spec.potential);
    d.lagrangian = canonical(d.kinetic - d.potential);
    if (wh.any) { // wheels.hpp: T the total, L Routh's function
        ex hw = 0, hw_driven = 0;
        for (int i = 0; i < 3; ++i) {
            hw += wh.h[i] * d.omega[i];
            hw_driven += wh.h_driven[i] * d.omega[i];
        }
        d.lagrangian = canonical(T / 2 + hw + wh.routh - d.potential);
        d.kinetic = canonical(T / 2 + hw_driven + wh.kinetic);
    }
    d.energy = canonical(d.kinetic + d.potential);

    // p = dL/dq_dot, M = dp/dq_dot
    for (int i = 0; i < 3; ++i)
        d.momenta[i] = canonical(d.lagrangian.diff(s.qd[i]));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            d.mass_matrix[i][j] = canonical(d.momenta[i].diff(s.qd[j]));

    d.generalized_force = generalized_force(spec, d);
    const vector3 reaction = motor_force(d); // torque-driven wheels: wheels.hpp

    // f_i = dL/dq_i - sum_j (dp_i/dq_j) q_dot_j + Q_i, so that d/dt p_i - dL/dq_i = Q_i reads
    // M q_ddot = f.
    for (int i = 0; i < 3; ++i) {
        ex f = d.lagrangian.diff(s.q[i]) + d.generalized_force[i] + reaction[i];
        for (int j = 0; j < 3; ++j)
            f -= d.momenta[i].diff(s.q[j]) * s.qd[j];
        if (wh.driven) f -= d.momenta[i].diff(s.t); // a rate drive: p depends on t
        d.forcing[i] = canonical(f);
        ex el = -d.forcing[i];
        for (int j = 0; j < 3; ++j)
            el += d.mass_matrix[i][j] * s.qdd[j];
        d.euler_lagrange[i] = canonical(el);
    }

    hamiltonian_side(d);

    for (int i = 0; i < 3; ++i)
        if (canonical(d.lagrangian.diff(s.q[i])).is_zero() && d.generalized_force[i].is_zero())
            d.cyclic.push_back(i);
    return d;
}

} // namespace rotgen
