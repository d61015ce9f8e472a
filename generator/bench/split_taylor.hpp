// rotgen bench: the structure-exploiting methods in the plan — split2, split4, split6 (the exact
// free-body flow with kicks, runtime/steppers/splitting.hpp) on the body form with the quaternion,
// and taylor (runtime/steppers/taylor.hpp) on the main variant — when the model admits them, by
// the very checks `rotgen simulate` makes (run/split_run.hpp, run/kernels.hpp); otherwise the
// refusal simulate would give, which the plan and the summary quote.
#pragma once

#include "bench/variants.hpp"
#include "scene/scene.hpp"

#include <ginac/ginac.h>

#include <array>
#include <optional>
#include <string>

namespace rotgen::bench {

struct split_taylor_methods {
    std::optional<std::string> split_refusal;  // why split2/4/6 are left out; none: they run
    std::array<double, 3> moments{};           // the principal moments the split system uses
    std::optional<std::string> taylor_refusal; // why taylor is left out; none: it runs
};

// The split methods: check_split_model on the scene with integrator split2, at the scene's
// parameter values (`values`). Fills split_refusal or moments.
void check_split(const scene_spec& scene, const GiNaC::exmap& values, split_taylor_methods& m);

// The Taylor method on `main` (the scene's form, as simulate runs it): its rhs emitted with the
// Taylor coefficients; when that works, "taylor" joins main's outputs, else taylor_refusal is set.
void check_taylor(const model_spec& spec, variant& main, split_taylor_methods& m);

} // namespace rotgen::bench
