// rotgen — small rules of a member's run (run/engine.cpp) that other parts share.
#pragma once

#include "scene/scene.hpp"

#include "result.hpp"

namespace rotgen {

// t is the end time or beyond it, in the direction of the run (backward when t_end < t_start).
bool reached_end(const scene_spec& scene, double t);

// s += more, counter by counter.
void add_stats(step_stats& s, const step_stats& more);

} // namespace rotgen
