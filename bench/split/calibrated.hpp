// A method calibrated as `rotgen simulate` calibrates a run of the body form (quaternion, ω):
// step_control.hpp's calibrate() with the quaternion an attitude, ω one vector and the run's span
// (both benches run t = 0..10), so that rtol means the error at the samples for every method
// (docs/integrators.md, "What a tolerance means").
// Shared by bench/split/split_bench.cpp and control_bench.cpp.
#pragma once

#include "step_control.hpp"

#include <cstddef>

template <class M> M calibrated(M m, double span = 10) {
    constexpr signed char q = rotgen::error_layout::attitude;
    rotgen::calibrate(m, rotgen::error_layout{{q, q, q, q, 0, 0, 0}, {}, span});
    m.max_steps = std::size_t(100000000);
    return m;
}
