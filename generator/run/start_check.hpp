// rotgen — the check of a run's start before it integrates (run/engine.cpp).
#pragma once

#include "run/kernels.hpp"
#include "run/kinematics.hpp"
#include "scene/scene.hpp"

#include <euler_sequence.hpp> // runtime

#include <Eigen/Dense>

#include <vector>

namespace rotgen {

// What the check reads of the run: the scene, its monitored invariants, the model's sequence and
// the member's inertia tensor.
struct start_context {
    const scene_spec& scene;
    const std::vector<invariant>& invariants;
    const euler_sequence& sequence;
    const Eigen::Matrix3d& inertia;
};

// The start k in the form cf (state y, the form's parameter values) must be finite where the run
// computes from it: throws user_error at the scene's `initial` otherwise.
void check_finite_start(const start_context& c, const initial_kinematics& k,
                        const compiled_form& cf, const std::vector<double>& parameters,
                        const Eigen::VectorXd& y);

} // namespace rotgen
