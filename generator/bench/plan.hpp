// rotgen bench: the plan the driver runs (plan.txt): the configurations (integrator x tolerance or
// step x scalar type x variant, and the peers Boost.Odeint and SUNDIALS CVODE on the same
// kernels), the reference and the long runs.
#pragma once

#include "bench/bench.hpp"
#include "bench/initial_state.hpp"
#include "bench/split_taylor.hpp"
#include "bench/variants.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace rotgen::bench {

struct bench_plan {
    double t0 = 0, t1 = 0;
    double nu = 1;         // the fastest rate of the motion; fixed steps are h = c / nu
    double target = 0.02;  // seconds per timed loop
    int repeats = 7;       // timed loops per configuration (>= 5)
    std::string text;      // plan.txt
    std::size_t lines = 0; // configurations
    std::size_t ref_variant = 0;
    std::vector<std::string> drift_labels; // the long runs, in order
    std::vector<std::string> left_out;     // "split2, split4, split6: <why>", "taylor: <why>"
};

// The plan for the scene's variants; sets each variant's method bits (what the driver compiles
// for it). `conservative`: no damping and no torque; `extra`: whether split2/4/6 and taylor run.
// The tolerances of the Taylor method's rows (the full plan's; --quick runs two of them).
std::vector<double> taylor_tolerances();

bench_plan make_plan(const scene_spec& scene, const model_spec& spec,
                     const GiNaC::exmap& parameter_values, const kinematics& k0,
                     const bench_options& opt, bool conservative, variant_set& set,
                     const split_taylor_methods& extra);

} // namespace rotgen::bench
