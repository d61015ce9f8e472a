// rotgen — forms/: the small exact algebra the four forms share (internal to this stage).
//
// 3-vectors and 3x3 matrices of GiNaC expressions, composed without expanding (lowering computes
// shared subexpressions once); the inline L D L^T solve of the `solve` strategy; the helpers that
// fill a form_expressions (outputs, names); and the Hamiltonian pieces l, omega, q_dot, p_dot that
// the hamiltonian and reduced forms both use. Conventions as in forms.hpp: z-x-z Euler angles,
// omega = J q_dot in body axes (5.30).
#pragma once

#include "forms/forms.hpp"

#include <ginac/ginac.h>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace rotgen::form_detail {

using vec = std::array<GiNaC::ex, 3>;

vec mat_vec(const matrix3& m, const vec& v);   // m v
vec mat_t_vec(const matrix3& m, const vec& v); // m^T v
vec cross(const vec& a, const vec& b);         // a x b
GiNaC::ex dot(const vec& a, const vec& b);     // a . b

// M = L D L^T for a symmetric 3x3 M (lower triangle read), L unit lower triangular.
struct ldlt {
    GiNaC::ex l10, l20, l21, d0, d1, d2;
};
ldlt ldlt_factor(const matrix3& M);
// x with L D L^T x = b: forward substitution, diagonal, back substitution.
vec ldlt_solve(const ldlt& F, const vec& b);

std::vector<GiNaC::ex> flat(const matrix3& m);               // row-major
std::vector<std::string> matrix_names(const std::string& m); // m11, m12, ..., m33
void add_output(form_expressions& f, const std::string& name, std::vector<GiNaC::ex> values,
                std::vector<std::string> names);

// A gyrostat's (derive/wheels.hpp) total kinetic energy 1/2 omega . I omega (+ h_driven . omega
// + the wheels' own terms) and total angular momentum I omega (+ h), given Iw = I omega; the bare
// body's when the model has no wheels.
GiNaC::ex kinetic_of(const derivation& d, const vec& w, const vec& Iw);
vec momentum_of(const derivation& d, const vec& Iw);

// H = 1/2 l . I^{-1} l + V with l = J^{-T} p: the Hamiltonian form's pieces, composed.
struct hamilton_parts {
    vec l, w, qdot, pdot; // l = J^{-T} p, omega = I^{-1} l, q_dot = dH/dp, p_dot = -dH/dq + Q
};
hamilton_parts hamilton(const derivation& d);

// The forms (each appends its state, rates, notes and outputs to f).
void build_lagrangian(const model_spec& spec, const derivation& d, form_expressions& f);
void build_hamiltonian(const model_spec& spec, const derivation& d, form_expressions& f);
void build_reduced(const model_spec& spec, const derivation& d, form_expressions& f);
void build_body(const model_spec& spec, const derivation& d, form_expressions& f, bool orientation);
// The torque-driven wheels' momenta appended to the state (forms/wheel_states.cpp): p_k' = tau_k
// with in_state(tau_k) in the form's variables; their parameters p_<wheel> leave f.parameters.
void add_wheel_states(const model_spec& spec, form_expressions& f,
                      const std::function<GiNaC::ex(const GiNaC::ex&)>& in_state);
// user_error where the form takes no torque-driven wheel (the reduced form).
void refuse_torque_wheels_in(const model_spec& spec, form_kind form);

// The linear rotor in chart 1 (form rotor) or 2 (rotor_x): forms/rotor.cpp.
void build_rotor(const model_spec& spec, form_expressions& f, int chart);

} // namespace rotgen::form_detail
