// rotgen — stage 3: scene selection. The expressions one form of the equations of motion needs.
//
// A form fixes the state vector y and gives dy/dt and the optional outputs as GiNaC expressions in
// y, t and the parameters. Expressions are composed, not expanded: q_ddot = J^{-1} (I^{-1} (J^{-T}
// f)) keeps f, J^{-T} f, ... as shared subexpressions, which lowering then computes once.
//
//   lagrangian   y = (phi, theta, psi, phi_dot, theta_dot, psi_dot), M(q) q_ddot = f(t, q, q_dot).
//                Strategy `explicit`: q_ddot = J^{-1} I^{-1} J^{-T} f   (M^{-1} = J^{-1} I^{-1}
//                J^{-T}, M = J^T I J, J = d omega / d q_dot from (5.30); no general symbolic
//                inverse). Strategy `solve`: M and f, solved numerically (LDL^T) by the generated
//                code.
//   hamiltonian  y = (phi, theta, psi, p_phi, p_theta, p_psi):
//                l = J^{-T} p, omega = I^{-1} l, q_dot = J^{-1} omega = dH/dp,
//                p_dot_i = -omega . dl/dq_i - dV/dq_i + Q_i(t, q, q_dot).
//   reduced      the Hamiltonian form without its cyclic coordinates (Routh): their equations are
//                dropped, their momenta become parameters (conserved), their rates an optional
//                output `ignored_rates`. Heavy symmetric top: y = (theta, p_theta).
//   body         y = (qw, qx, qy, qz, omega1, omega2, omega3), no Euler angles:
//                I omega_dot = tau - omega x I omega  (Euler's equations, full tensor),
//                q_dot = 1/2 q (x) (0, omega)         (quaternion kinematics, body angular
//                velocity). The unit quaternion q = (qw, qx, qy, qz) rotates body axes into space
//                axes: R(q) = A^T, A the passive body <- space matrix of (5.25); from Euler angles
//                q = qz(phi) (x) qx(theta) (x) qz(psi). Every use of q divides by |q|^2, so the
//                equations hold for any non-zero q.
//                tau = r_com x (-M g e) for the gravity shorthand, e = the space vertical in body
//                axes = the third row of R(q) (smooth everywhere); other potentials, damping and
//                torques that depend on the angles go through the Euler-angle chart
//                (tau = -J^{-T} dV/dq + J^{-T} Q, angles from q): singular at theta = 0, pi.
//                A body with no orientation-dependent torque has y = (omega1, omega2, omega3)
//                unless the orientation is asked for (the `rotation` output).
//
// Conventions (5.3, 5.25, 5.30): z-x-z Euler angles, passive A = Az(psi) Ax(theta) Az(phi), omega
// in body axes. The Euler-angle forms are singular at theta = 0, pi (det J = -sin theta).
#pragma once

#include "derive/derive.hpp"
#include "forms/form_kind.hpp"
#include "spec/spec.hpp"

#include <ginac/ginac.h>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace rotgen {

enum class lagrangian_strategy { explicit_inverse, solve };

const char* to_string(lagrangian_strategy s);

// The quaternion symbols of the body form (qw, qx, qy, qz); not coordinates of the derivation.
const std::array<GiNaC::realsymbol, 4>& quaternion_symbols();

struct state_variable {
    std::string name; // as in DESIGN.md: phi, theta_dot, p_psi, qw, omega1, ...
    GiNaC::ex symbol;
    std::string description;
};

// A parameter of the generated code: the model's, or a conserved momentum of the reduced form.
struct form_parameter {
    std::string name;
    GiNaC::ex symbol;
    double value = 0;
    std::string description;
    bool specialisable = true; // false for conserved momenta (initial data, not model constants)
};

struct form_output {
    std::vector<GiNaC::ex> values;
    std::vector<std::string> names; // one per value, for documentation
    // Equivalent expressions by other routes; the emitter keeps whichever lowers to fewer
    // operations.
    std::vector<std::vector<GiNaC::ex>> alternatives;
};

struct form_expressions {
    angle_convention angles; // the model's (spec.angles): the state's angle names and sequence
    form_kind form = form_kind::lagrangian;
    lagrangian_strategy strategy = lagrangian_strategy::explicit_inverse;
    std::vector<state_variable> state;
    std::vector<form_parameter> parameters;
    GiNaC::ex time; // the time symbol

    // dy/dt in terms of y, t and the parameters; alternative_rates are the same by other routes
    // (the emitter keeps, for each function, whichever lowers to fewer operations).
    std::vector<GiNaC::ex> rates;
    std::vector<std::vector<GiNaC::ex>> alternative_rates;
    std::vector<std::string> rate_names;
    matrix3 mass;    // solve strategy: M(q), factored inline in rates
    vector3 forcing; // solve strategy: f(t, q, q_dot)

    // energy, momenta, mass_matrix, omega, rotation, ignored_rates — those this form can give.
    std::map<std::string, form_output> outputs;
    std::map<std::string, std::string> unavailable; // output -> why this form cannot give it

    std::vector<std::string> notes; // documentation for the header: layout, singularities, ...
    // Body form: part of the torque or potential goes through the Euler-angle chart, so this form
    // too is singular at theta = 0, pi.
    bool uses_euler_chart = false;
};

// The names of every output the emitter knows, in a fixed order.
const std::vector<std::string>& output_names();

// Builds the form. `orientation` asks the body form to keep the quaternion even for a free body.
// Throws user_error when the model has no such form (e.g. reduced without cyclic coordinates).
form_expressions build_form(const model_spec& spec, const derivation& d, form_kind form,
                            lagrangian_strategy strategy, bool orientation);

// The analytic Jacobian d rates_i / d y_k, row-major (state_size x state_size): symbolic
// derivatives; for the `solve` strategy d q_ddot/d y_k = M^{-1} (df/dy_k - dM/dy_k q_ddot), the
// same inline LDL^T as the rates. An entry that is exactly 0 is structurally zero.
std::vector<GiNaC::ex> jacobian(const form_expressions& f);
// The same for other rates of the same form (one of f.alternative_rates).
std::vector<GiNaC::ex> jacobian(const form_expressions& f, const std::vector<GiNaC::ex>& rates);

// The parameter Jacobian d rates_i / d p_j of `rates` (f.rates or one of f.alternative_rates),
// row-major (state_size x parameters.size()), `parameters` the symbols of form_parameter: GiNaC
// diff; for the `solve` strategy d q_ddot/d p_j = M^{-1} (df/dp_j - dM/dp_j q_ddot), as jacobian().
std::vector<GiNaC::ex> parameter_jacobian(const form_expressions& f,
                                          const std::vector<GiNaC::ex>& rates,
                                          const std::vector<GiNaC::ex>& parameters);

// The rotation matrix A(q) of the sequence c ((5.25) for z-x-z), row-major.
std::array<GiNaC::ex, 9> rotation_matrix(const angle_convention& c);

} // namespace rotgen
