// rotgen — derive/: the linear rotor (Example 5.4, §5.5), two angles q = (phi, theta).
//
// The rotor's line is the body axis 3 of the z-x-z Euler angles; its direction in space is the
// third row of A (5.25), n = (sin theta sin phi, -sin theta cos phi, cos theta), and with I the
// moment across the line (spec.hpp: rotor_moment)
//   T = 1/2 I (theta_dot^2 + sin^2 theta phi_dot^2) = 1/2 I |n_dot|^2,
//   L = T - V(phi, theta),  p = (I sin^2 theta phi_dot, I theta_dot),  M = diag(I sin^2 theta, I),
//   M q_ddot = f,  f_i = dL/dq_i - sum_j (dp_i/dq_j) q_dot_j   (Euler-Lagrange, no forces),
//   H = p_theta^2 / (2 I) + p_phi^2 / (2 I sin^2 theta) + V,  q_dot = dH/dp,  p_dot = -dH/dq.
// Singular at theta = 0, pi (M_11 = I sin^2 theta), where the line passes the chart's pole.
//
// Chart 2 is the same sphere with its pole on the x axis: angles (phi2, theta2) of the cyclically
// permuted direction (n_y, n_z, n_x) = (sin theta2 sin phi2, -sin theta2 cos phi2, cos theta2),
// so that the pole of chart 1 (n = +-e_z) lies on its equator. T has the same form in it; V is
// carried over when it depends on the angles through cos(theta) = n_z alone (gravity does), then
// V2 = V with cos(theta) = -sin(theta2) cos(phi2).
#pragma once

#include "spec/spec.hpp"

#include <ginac/ginac.h>

#include <array>
#include <optional>
#include <vector>

namespace rotgen {

struct rotor_derivation {
    int chart = 1;
    std::array<GiNaC::ex, 2> q, qd, qdd, p; // the coordinates' symbols (chart 2: its own)
    GiNaC::ex moment;                       // I
    GiNaC::ex kinetic, potential, lagrangian, energy, hamiltonian;
    std::array<GiNaC::ex, 2> momenta;                    // p = dL/dq_dot
    std::array<std::array<GiNaC::ex, 2>, 2> mass_matrix; // dp/dq_dot
    std::array<GiNaC::ex, 2> forcing;                    // f:  M q_ddot = f
    std::array<GiNaC::ex, 2> euler_lagrange;             // M q_ddot - f (= 0)
    std::array<GiNaC::ex, 2> hamilton_qdot, hamilton_pdot;
    std::vector<int> cyclic; // coordinates absent from L (their momentum conserved)
};

// V of the rotor in chart 2, or nullopt when V is not a function of cos(theta) alone (then a run
// cannot leave chart 1 at its pole).
std::optional<GiNaC::ex> rotor_potential_in_chart2(const model_spec& spec);

// The derivation in chart 1 or 2 (chart 2 requires rotor_potential_in_chart2). Pure.
rotor_derivation derive_rotor(const model_spec& spec, int chart = 1);

// Chart 2's symbols phi2, theta2, their rates, accelerations and momenta.
const std::array<GiNaC::realsymbol, 8>& rotor_chart2_symbols();

} // namespace rotgen
