// rotgen bench: the scene's initial state in every coordinate the variants use, in long double:
// run/kinematics.hpp's, the one initial-kinematics function (also `rotgen simulate`'s).
#pragma once

#include "run/kinematics.hpp"

namespace rotgen::bench {

using kinematics = rotgen::initial_kinematics;

} // namespace rotgen::bench
