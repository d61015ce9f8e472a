// rotgen — where sensitivities start: S(t0) = d y(t0)/d s for the scene's sensitivity keys s, and
// d P/d s for the form's parameters P (the model's, and the reduced form's cyclic momenta, which
// the initial values give), at a member's start.
//
// Exact: GiNaC differentiates the same start formulas that give the member's initial kinematics
// (run/kinematics.cpp: q_dot from the rates as given, J^{-1} omega or M(q)^{-1} p; then
// p = dL/dq_dot and omega = J q_dot, 5.30) and evaluates the derivatives at 30 digits; M^{-1}'s
// derivative is d q_dot = M^{-1} (d p - dM q_dot). The quaternion's derivative is the product rule
// on q_a(a0) (x) q_b(a1) (x) q_c(a2): d q_x(a)/da = 1/2 (0, e_x) (x) q_x(a).
// A key keeps sweep's meaning: a parameter key holds the other initial values at their numbers
// (the momenta still move with the inertia when the scene gives rates). `all_initial`: S(t0) = I.
#pragma once

#include "derive/derive.hpp"
#include "forms/forms.hpp"
#include "run/kinematics.hpp"
#include "scene/scene.hpp"

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace rotgen {

struct member_values; // run/engine.hpp

struct start_derivatives {
    Eigen::MatrixXd dy0; // n x k: d y(t0)/d s
    Eigen::MatrixXd dP;  // P x k: d (the form's parameters)/d s
};

// The keys' names: as written, or y0.<state name> for all_initial.
std::vector<std::string> sensitivity_key_names(const scene_spec& scene, const form_expressions& f);

// S(t0) and dP/ds of the form `f` at the member `values`, whose start is `k0`. Uses GiNaC: the
// caller holds symbolic_mutex() (run/prepared.hpp).
start_derivatives start_derivatives_of(const scene_spec& scene, const derivation& d,
                                       const form_expressions& f, const member_values& values,
                                       const initial_kinematics& k0);

} // namespace rotgen
