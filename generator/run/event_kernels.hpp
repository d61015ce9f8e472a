// rotgen — a scene's event expressions (scene/events.hpp) in the state of one form, for the
// compiled kernels (kernels.cpp emits one function rotgen_event_<i>(t, y, out) per event).
//
// Each name the expression uses becomes the form's expression for it: a state, an output of the
// form (energy, momenta, omega, ...) or a rate. The body form with its quaternion gives the
// Euler-angle quantities through the rotation matrix A (5.25), whose third column is
// (sin theta sin psi, sin theta cos psi, cos theta) and third row (sin theta sin phi,
// -sin theta cos phi, cos theta):
//   theta = acos A33,  phi = atan2(A31, -A32),  psi = atan2(A13, A23)   (phi, psi in (-pi, pi])
//   phi_dot = (omega1 A13 + omega2 A23) / sin^2 theta,  theta_dot = (omega1 A23 - omega2 A13) /
//   sin theta,  psi_dot = omega3 - phi_dot cos theta   (q_dot = J^-1 omega, 5.30)
//   p_phi = A13 l1 + A23 l2 + A33 l3,  p_theta = (A23 l1 - A13 l2) / sin theta,  p_psi = l3
//   (p = J^T l, l = I omega), with sin theta = sqrt(A13^2 + A23^2).
// The rates and p_theta are undefined at theta = 0, pi, as in the Euler-angle forms.
#pragma once

#include "forms/forms.hpp"
#include "scene/scene.hpp"

#include <ginac/ginac.h>

#include <vector>

namespace rotgen {

// One expression per scene event, in the symbols of the form's state, parameters and t.
// Throws user_error, at the event's `when`, when the form does not give a name it uses.
std::vector<GiNaC::ex> event_programs(const scene_spec& scene, const form_expressions& f);

} // namespace rotgen
