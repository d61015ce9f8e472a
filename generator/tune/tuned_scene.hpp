// rotgen tune: the scene lines that run a chosen configuration, and the tuned scene file.
#pragma once

#include "scene/scene.hpp"

#include <string>

namespace rotgen {

// "integrator: {method: dop853, rtol: 3e-09, atol: 3e-11}" (a fixed step: {method, step}).
std::string integrator_line(const integrator_spec& ig);

// The scene file's text with `form:` (when `with_form`) and `integrator:` set from `scene` (the
// resolved scene) and a relative model path rewritten for a file in `out_dir`. Comments are not
// kept.
std::string tuned_scene_text(const scene_spec& scene, const std::string& out_dir, bool with_form);

} // namespace rotgen
