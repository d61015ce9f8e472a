// rotgen bench: the scene's initial state in every coordinate the variants use, in long double.
//
// Angles are z-x-z Euler angles (5.3), A = Az(psi) Ax(theta) Az(phi) passive body <- space (5.25),
// omega in body axes (5.30); the quaternion is the runtime's quaternion_from_euler of the angles.
#pragma once

#include "derive/derive.hpp"
#include "scene/scene.hpp"

#include <Eigen/Geometry>

#include <array>

namespace rotgen::bench {

struct kinematics {
    std::array<long double, 3> q{}, qd{}, p{}, omega{};
    bool have_rates = true; // false at sin theta = 0 when the scene gives momenta or omega
    Eigen::Quaternion<long double> quat;
};

// The initial state, evaluated at 30 digits from the scene's decimal values: q, and q_dot from
// the given rates, momenta (M q_dot = p) or omega (q_dot = J^{-1} omega), then p = dL/dq_dot and
// omega (5.30) from them; omega as given when the scene gives it.
// shared with simulate: to be replaced by run/'s one initial-kinematics function
kinematics initial_kinematics(const scene_spec& scene, const derivation& d,
                              const GiNaC::exmap& parameters);

// The runs are in double (and float): initial values whose rates, momenta or kinetic energy
// (1/2 p . q_dot) overflow double are refused up front (user_error), as `simulate` does, rather
// than reported as a sweep of non-finite runs.
// shared with simulate: to be replaced by run/'s overflow check
void check_double_range(const scene_spec& scene, const kinematics& k);

} // namespace rotgen::bench
