// rotgen — what a scene's event does (scene/events.hpp): `every`, `after` and `action`.
//
//   every: T                       a time event at t = start + k T, k >= 1 (start: the scene's own
//                                  time.start, also after `simulate --from`); T > 0, an expression
//                                  in the model's parameters; exclusive with `when`
//   after: N                       the event acts (records, stops) from its N-th occurrence on
//                                  (N >= 1, default 1); earlier occurrences leave no record
//   action: stop | record
//   action: {impulse: [J1, J2, J3]}           an angular impulse in body axes: Delta L = J,
//                                             Delta omega = I^-1 J
//   action: {impulse_space: [Jx, Jy, Jz]}     the same in space axes
//   action: {set: {omega3: "omega3 / 2", parameters.k: "-k"}}
//                                  new values: names of one way of giving the attitude and of one
//                                  way of giving the angular velocity, as `initial:` takes them
//                                  (angles, q0..q3 or A; rates, momenta, omega1..3 or
//                                  omega_x..z), and parameters.<name> (not one the inertia
//                                  depends on)
// The values are expressions over the state before the event (angles, rates, momenta, omega),
// t and the model's parameters (a pulse strength that the equations do not use is a parameter of
// the model all the same, so that a sweep can vary it). run/actions.hpp applies them.
#pragma once

#include "scene/events.hpp"

namespace rotgen::scene_detail {

// Reads `every`, `after` and `action` of the event mapping n into e (e.name is set). Throws
// user_error at the offending key or value.
void read_event_action(const YAML::Node& n, event_spec& e, const model_spec& model,
                       const std::string& file);

} // namespace rotgen::scene_detail
