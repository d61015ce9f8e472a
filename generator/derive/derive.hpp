// rotgen — stage 2: the symbolic model and its derivation.
//
// From the model's inertia tensor I (body axes) and potential V(q):
//   omega = J(q) q_dot                                  (5.30)
//   T = 1/2 omega^T I omega                             (5.38), any symmetric I
//   L = T - V,  p = dL/dq_dot = M(q) q_dot,  M = J^T I J
//   M(q) q_ddot = f(q, q_dot, t),
//     f_i = dL/dq_i - sum_j (dp_i/dq_j) q_dot_j + Q_i   (Euler-Lagrange; Q the generalised force)
//   Q = -c .* q_dot + J^T tau                           (damping, body torque tau)
//   H(q, p) = 1/2 l^T I^{-1} l + V,  (a gyrostat's wheels: wheels.hpp)
//    l = J^{-T} p       (l the body angular momentum; no
//                                                        symbolic inverse of M is ever formed)
//   q_dot = dH/dp,  p_dot = -dH/dq + Q                  (Hamilton's equations)
//
// Conventions: z-x-z Euler angles q = (phi, theta, psi); passive A = Az(psi) Ax(theta) Az(phi)
// (5.25); omega in body axes. J is singular at theta = 0, pi (det J = -sin theta), so H and
// Hamilton's equations carry 1/sin(theta).
//
// Every expression is built from diff, subs and expand only, and brought to one canonical form
// (expanded, with sin^2 of phi and psi rewritten as 1 - cos^2), so results are reproducible.
#pragma once

#include "derive/wheels.hpp"
#include "spec/spec.hpp"

#include <ginac/ginac.h>

#include <array>
#include <vector>

namespace rotgen {

struct derivation {
    angle_convention angles;        // the model's (spec.angles): what q[0..2] are and are named
    matrix3 omega_jacobian;         // J = d omega / d q_dot
    vector3 omega;                  // (5.30), in q and q_dot
    GiNaC::ex kinetic;              // T (5.38), in q and q_dot
    GiNaC::ex potential;            // V, in q
    GiNaC::ex lagrangian;           // L = T - V
    GiNaC::ex energy;               // E = T + V, in q and q_dot
    vector3 momenta;                // p = dL/dq_dot
    matrix3 mass_matrix;            // M(q) = d p / d q_dot
    vector3 generalized_force;      // Q, in t, q and q_dot
    vector3 forcing;                // f(q, q_dot, t):  M q_ddot = f
    vector3 euler_lagrange;         // M q_ddot - f  (each = 0)
    matrix3 inverse_omega_jacobian; // J^{-1}: q_dot = J^{-1} omega
    matrix3 inverse_inertia;        // I^{-1} (adjugate / determinant; 1/I_ii when diagonal)
    vector3 body_momentum;          // l = I omega = J^{-T} p, in q and p
    GiNaC::ex hamiltonian;          // H(q, p)
    vector3 hamilton_qdot;          // dH/dp
    vector3 hamilton_pdot;          // -dH/dq + Q(q, dH/dp)
    std::vector<int> cyclic; // indices of coordinates absent from L and Q (momentum conserved)
    // A gyrostat's wheels (wheels.hpp): h, its rate, the extra kinetic terms. With wheels, T is
    // the total kinetic energy, L Routh's function (free wheels' angles eliminated), I above the
    // body's I_e (+ J a a^T of the rate-driven wheels), l = J^{-T} p = I_e omega + h and
    // H = 1/2 (l - h)^T I_e^{-1} (l - h) - routh + V.
    wheel_terms wheels;
};

// Derives everything above. Pure: depends only on the spec.
derivation derive(const model_spec& spec);

// The canonical form: expanded, sin(phi)^2 and sin(psi)^2 replaced by 1 - cos^2.
GiNaC::ex canonical(const GiNaC::ex& e);

// d/dt of an expression in (t, q, q_dot): sum_i (d/dq_i) q_dot_i + (d/dq_dot_i) q_ddot_i + d/dt.
GiNaC::ex time_derivative(const GiNaC::ex& e);

} // namespace rotgen
