// rotgen — scene/: `initial:` of a three-angle body. The attitude is given one way:
//   the model's angles (phi, theta, psi for z-x-z; the model's names otherwise),
//   a quaternion q0, q1, q2, q3 (scalar first, R(q) = A^T as the records' q0..q3; normalised,
//   refused where | |q| - 1 | > 1e-6), or
//   A: [[..], [..], [..]] the passive matrix of (5.25), row i = body axis i in space axes
//   (refused unless orthonormal with det +1 to 1e-9);
// the angular velocity one way: the angles' rates (<name>_dot), the momenta (p_<name>, with the
// attitude as angles only), body omega (omega1..3) or space omega (omega_x, omega_y, omega_z).
// A quaternion or A becomes the angles of the model's sequence, space omega becomes body omega
// (omega_body = A omega_space), each as an exact expression of the values written
// (expr/angles.hpp's angles_of_matrix), so that the start (run/kinematics, run/quad_start) is
// computed from them at 30 digits or in quad precision as from angles written by hand.
#pragma once

#include "scene/values.hpp"

namespace rotgen::scene_detail {

// Reads `initial` (the mapping n; `key` the location of its key) into scene.angles, .initial,
// .initial_rates and their written values. user_error for anything missing, given twice or out of
// range.
void read_initial_state(scene_spec& scene, const YAML::Node& n, const source_location& key,
                        const value_reader& values, const std::string& file);

// A free or torque-driven wheel's momentum p_<wheel> written in `initial`
// (scene/wheel_initial.cpp): the value of the model parameter of that name; refused when
// `parameters` gives it too. Or its rate <wheel>_dot relative to the body: p_<wheel> = J (a .
// omega0 + <wheel>_dot), omega0 the body's initial angular velocity (after read_initial_state), J
// and a at the scene's parameters.
void read_wheel_initial(scene_spec& scene, const YAML::Node& n, const YAML::Node& parameters,
                        const value_reader& values, const std::string& file);

// "model 'M' carries wheels: <instead> (its momenta p_phi.. include the wheels' h)".
std::string wheel_momenta_refusal(const model_spec& model, const std::string& instead);

// A model with wheels in the hamiltonian form must keep its chart (switch_chart: false).
void check_wheel_scene(const scene_spec& scene);

} // namespace rotgen::scene_detail
