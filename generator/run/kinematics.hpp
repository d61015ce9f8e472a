// rotgen — the initial state of a scene in every coordinate the forms use, computed once, exactly.
//
// A scene gives the Euler angles (z-x-z, 5.3; radians) and one of: the rates q_dot, the momenta
// p, or the body angular velocity omega (5.30). From those, with the scene's parameter values:
//   q_dot = M(q)^{-1} p  (M = dp/dq_dot)   or   q_dot = J^{-1} omega  (J = d omega/d q_dot)
//   p = dL/dq_dot (5.74-5.76 for the heavy top),   omega (5.30).
// Computed with GiNaC at 30 significant digits from the exact decimals the scene file wrote, and
// held in long double: `rotgen simulate` rounds to double, `rotgen bench` uses long double for its
// long-double runs and its references. At theta = 0 or pi (|sin theta| < 1e-12) q_dot and p are
// undefined: `have_rates` is false and only the angles, the quaternion and a given omega are set.
#pragma once

#include "derive/derive.hpp"
#include "forms/forms.hpp"
#include "scene/scene.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <array>
#include <string>
#include <vector>

namespace rotgen {

struct initial_kinematics {
    std::array<long double, 3> q{}, qd{}, p{}, omega{};
    bool have_rates = true;
    Eigen::Quaternion<long double> quat; // body -> space, from the angles (scalar first: w x y z)
    // The torque-driven wheels' momenta p_<wheel> (states of the run), by name.
    std::vector<std::pair<std::string, long double>> wheels;
};

// The exact value of a scene's number: the expression it was written as while `current` is still
// its value (a caller may have changed it since: a sweep member), else the shortest decimal that
// reads back as `current` (9.81 -> 981/100).
GiNaC::ex exact_scene_value(double current, const written_value& written);

initial_kinematics initial_kinematics_of(const scene_spec& scene, const derivation& d);

// q_dot = M^{-1} p solved in long double, each rate as the 22-digit decimal text the start
// continues from (both initial_kinematics_of and run/quad_start.cpp read it back exactly).
std::array<std::string, 3> rates_text(const Eigen::Matrix<long double, 3, 3>& M,
                                      const Eigen::Matrix<long double, 3, 1>& p);

// Refuses (user_error at the scene's `initial`) initial values whose rates, momenta, omega or
// kinetic energy (1/2 p . q_dot) overflow double: the runs are in double.
void check_double_range(const scene_spec& scene, const initial_kinematics& k);

// A member's inertia tensor (its parameter values) must be physical: no negative or (but for a
// linear rotor) zero principal moment, the triangle inequality. Throws user_error ("rejected: ...",
// located at the scene) otherwise.
void check_physical_inertia(const scene_spec& scene, const Eigen::Matrix3d& inertia);

// A parameter of the scene (a model parameter, with the scene's overrides) or a conserved momentum
// p_<angle> (the reduced form's parameters), in long double. std::logic_error for another name.
long double scene_parameter_value(const scene_spec& scene, const initial_kinematics& k,
                                  const std::string& name);

// The values of a form's parameters for one member: its model parameter values (model_values,
// in the order of scene.model.parameters, exact to long double) and, for the reduced form, the
// conserved momenta p_<angle> of k, rounded to double. user_error at the scene's `initial` when
// the reduced form is started without momenta; std::logic_error for a name that is neither.
std::vector<double> form_parameter_values(const scene_spec& scene,
                                          const std::vector<long double>& model_values,
                                          const std::vector<form_parameter>& parameters,
                                          const initial_kinematics& k);

// A state variable of any form (phi .. psi, phi_dot .., p_phi .., omega1..3, qw qx qy qz) from
// the initial kinematics, the angles named by c. std::logic_error for another name.
long double state_value(const initial_kinematics& k, const angle_convention& c,
                        const std::string& name);

// A torque-driven wheel's momentum (run/wheel_states.cpp): k.wheels at the start, the parameters
// p_<wheel> of the member (model_values in the order of the model's parameters); after a change of
// chart, the values the state y of form f holds.
void start_wheel_states(const scene_spec& scene, const std::vector<long double>& model_values,
                        initial_kinematics& k);
void carry_wheel_states(const scene_spec& scene, const form_expressions& f,
                        const Eigen::VectorXd& y, initial_kinematics& k);

// The state vector of form f (a three-angle form's, or a linear rotor's) from the initial
// kinematics, rounded to double; `scene_form` names the scene's form in the logic_error of a start
// without rates in a form that needs them (decide_chart in run/engine.cpp makes it unreachable).
Eigen::VectorXd form_state(const form_expressions& f, const initial_kinematics& k,
                           const angle_convention& c, form_kind scene_form);

} // namespace rotgen
