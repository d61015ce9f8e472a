// rotgen — derive/: the terms a gyrostat's wheels add (spec.wheels, spec/wheels_input.cpp).
//
// With wheel k on the unit body axis a_k, axial moment J_k and angle alpha_k relative to the body,
//   T = 1/2 omega^T I omega + sum_k 1/2 J_k (a_k . omega + alpha_dot_k)^2,
//   p_k = dT/d alpha_dot_k = J_k (a_k . omega + alpha_dot_k),   h = sum_k p_k a_k (body axes).
// A free wheel's angle is cyclic: p_k is conserved, a parameter of the run, and Routh's function
// R = L - sum p_k alpha_dot_k = 1/2 omega^T I omega + h . omega - sum p_k^2 / (2 J_k) - V
// gives the body's equations in the three angles. A `rate` drive prescribes alpha_dot_k =
// Omega_k(t): no coordinate, the body's inertia gains J_k a_k a_k^T and h the term
// J_k Omega_k a_k. So, with I_e = I + sum_rate J a a^T,
//   L = 1/2 omega^T I_e omega + h . omega + sum_rate 1/2 J Omega^2 - sum_free p^2 / (2 J) - V,
//   T = 1/2 omega^T I_e omega + h_rate . omega + sum_rate 1/2 J Omega^2 + sum_free p^2 / (2 J)
//     (the total kinetic energy, body and wheels), p_q = J^T (I_e omega + h),
//   Euler:  I_e omega_dot + omega x (I_e omega + h) = tau - h_dot,  h_dot = sum_rate J Omega' a.
// A `torque` drive tau_k (in t, the angles, their rates, omega) is a free wheel whose momentum
// p_k is a state with p_k' = tau_k (the generalised force on its angle). In (q, alpha) the motor's
// virtual work is tau_k d alpha_k, so the Hamiltonian side (p_q = J^T (I_e omega + h)) gains
// nothing but p_k' = tau_k; Routh's function, whose p_k now varies, gains -J^T a_k tau_k in the
// Lagrangian forcing: the body feels the reaction `motor` = -sum tau_k a_k, and
//   I_e omega_dot + omega x (I_e omega + h) = tau - sum_torque tau_k a_k - h_dot.
#pragma once

#include "spec/spec.hpp"

#include <vector>

namespace rotgen {

struct wheel_terms {
    bool any = false;      // the model has wheels
    bool driven = false;   // some wheel has a `rate` drive (L depends on t; H is not the energy)
    bool torqued = false;  // some wheel has a `torque` drive (its p_k a state; motor below)
    vector3 h;             // sum_k p_k a_k, in t and the parameters
    vector3 h_driven;      // the rate drives' part, sum_rate J Omega a
    vector3 h_dot;         // dh/dt = sum_rate J Omega'(t) a
    vector3 motor;         // the motors' reaction on the body, -sum_torque tau_k a_k (body axes)
    GiNaC::ex kinetic = 0; // T - 1/2 omega^T I_e omega - h_driven . omega (in t, parameters)
    GiNaC::ex routh = 0;   // L - 1/2 omega^T I_e omega - h . omega + V
};

// The terms above. Pure.
wheel_terms wheel_terms_of(const model_spec& spec);

// I_e = I + sum_rate J a a^T.
matrix3 gyrostat_inertia(const model_spec& spec);
// The spec with I_e = I + sum_rate J a a^T as its inertia (spec itself when no wheel is driven).
model_spec gyrostat_body(const model_spec& spec);

// Each wheel's axial momentum p_k and rate alpha_dot_k, given body omega.
std::vector<GiNaC::ex> wheel_momenta(const model_spec& spec, const vector3& omega);
std::vector<GiNaC::ex> wheel_rates(const model_spec& spec, const vector3& omega);

// The names a gyrostat adds to what a scene may record: h1 h2 h3, and per wheel <name>_dot and
// p_<name> (empty without wheels).
std::vector<std::string> wheel_record_names(const model_spec& spec);

// User error at the first torque-driven wheel: `what` does not take it; `instead` says what does.
void refuse_torque_wheels(const model_spec& spec, const std::string& what,
                          const std::string& instead);

// The torque-driven wheels, in model order, and their torques tau_k (in t, the angles, their
// rates and omega1..3): the states p_<wheel> a form appends, and their rates.
std::vector<const wheel_spec*> torque_wheels(const model_spec& spec);
std::vector<GiNaC::ex> wheel_torques(const model_spec& spec);

} // namespace rotgen
