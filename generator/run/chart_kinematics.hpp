// rotgen — the state across a change of chart (run/engine.cpp's switch between an Euler-angle form
// and the body form near theta = 0, pi). z-x-z Euler angles (5.3), body omega (5.30), the
// quaternion q of the body form (R(q) = A^T, A of (5.25)). Every function takes the model's
// sequence (run/angle_chart.hpp's sequence_of(model.angles)).
#pragma once

#include "forms/form_kind.hpp"
#include "run/kinematics.hpp"

#include <euler_sequence.hpp> // runtime

#include <Eigen/Dense>

namespace rotgen {

// The initial kinematics of a continuation in the body form from an Euler-angle state (q, q_dot
// from f): omega = J q_dot (5.30).
initial_kinematics continuation(const euler_sequence& s, const Eigen::VectorXd& y,
                                const Eigen::VectorXd& dydt);

// The initial kinematics in the Euler-angle chart from a body-form state (quaternion, omega):
// q_dot = J^{-1} omega, p = J^T I omega (5.30); needs |sin theta| away from 0.
initial_kinematics from_body(const euler_sequence& s, const Eigen::VectorXd& y,
                             const Eigen::Matrix3d& inertia);

// |sin theta| of a state of the given form (Euler-angle forms: theta is y[1]).
double sin_theta_of(const euler_sequence& s, form_kind form, const Eigen::VectorXd& y);

// sin_theta_of(form, y) < bound (0 < bound < 1), without a sine where theta is plainly far from the
// singular set (a run asks it at every sample): the same answer.
bool sin_theta_below(const euler_sequence& s, form_kind form, const Eigen::VectorXd& y,
                     double bound);

} // namespace rotgen
