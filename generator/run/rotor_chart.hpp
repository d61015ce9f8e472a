// rotgen — run/: the two charts of a linear rotor's sphere of directions (derive/rotor.hpp).
//
// Chart 1 (form rotor): y = (phi, theta, phi_dot, theta_dot), the line's direction
// n = (sin theta sin phi, -sin theta cos phi, cos theta) (third row of A, 5.25). Chart 2 (form
// rotor_x): the same angles of the permuted direction m = (n_y, n_z, n_x), so its pole is the x
// axis and chart 1's pole (n = +-e_z) is on its equator. A run of chart 1 continues in chart 2
// near theta = 0, pi exactly as the Euler-angle forms continue in the body form (run/engine.cpp:
// below |sin theta| = 0.1 at a sample, back above 0.3); the change of chart is exact geometry:
// n and n_dot are the same vectors in both.
#pragma once

#include "forms/form_kind.hpp"
#include "run/kinematics.hpp"
#include "scene/scene.hpp"

#include <Eigen/Dense>

#include <string>

namespace rotgen {

bool is_rotor_form(form_kind f);

// The form a run leaves the scene's form for near its singularity: chart 2 for a rotor, the body
// form for the Euler-angle forms.
form_kind other_chart(form_kind scene_form);

// Whether a rotor's run can change chart: its potential must be expressible in chart 2.
bool rotor_can_switch(const scene_spec& scene);

// The initial kinematics of a rotor scene (angles and rates as written, exact to long double):
// q = (phi, theta, 0), q_dot = (phi_dot, theta_dot, 0), p = (I sin^2 theta phi_dot, I theta_dot, 0)
// with the moment I at the scene's parameter values; omega is not defined (0).
initial_kinematics rotor_initial_kinematics(const scene_spec& scene);

// The state of the rotor form `form` (either chart) from chart-1 kinematics.
Eigen::VectorXd rotor_state(form_kind form, const initial_kinematics& k);

// |sin theta| of chart 1 for a state of either chart: sqrt(n_x^2 + n_y^2).
double rotor_sin_theta(form_kind form, const Eigen::VectorXd& y);

// The same direction and rate in the other chart.
Eigen::VectorXd rotor_other_chart(form_kind from, const Eigen::VectorXd& y);

// The message for a start at chart 1's pole that cannot change chart.
std::string rotor_pole_message(double theta);

} // namespace rotgen
