// rotgen — scene/: what a scene of a linear rotor (Example 5.4; derive/rotor.hpp) may say.
//
// A rotor's state is (phi, theta, phi_dot, theta_dot), the angles of its line (z-x-z, the line
// the body axis 3): `initial:` gives exactly these four, its form is `rotor`, and a recorded
// quantity must be defined for a body without axes beyond its line. Internal to the scene stage.
#pragma once

#include "scene/scene.hpp"
#include "scene/values.hpp"

#include <yaml-cpp/yaml.h>

#include <string>

namespace rotgen::scene_detail {

// `form:` of a rotor (only `rotor`) or of another body (not `rotor`): user_error at n.
void check_rotor_form(const scene_spec& scene, const YAML::Node& n, const std::string& file);

// Reads the rotor's `initial:` (the mapping n, the key `key` for the message about missing names)
// into scene.angles (phi, theta, 0) and scene.initial_rates (phi_dot, theta_dot, 0), as rates.
void read_rotor_initial(scene_spec& scene, const YAML::Node& n, const source_location& key,
                        const value_reader& values, const std::string& file);

// Why `name` cannot be recorded for a rotor, or "" when it can.
std::string rotor_unrecordable(const std::string& name);

// The integrators a rotor can run: not the split methods (they step a three-axis body).
void check_rotor_integrator(const scene_spec& scene);

} // namespace rotgen::scene_detail
