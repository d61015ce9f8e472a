// rotgen — a member's initial kinematics (run/kinematics.hpp) in quad precision, without GiNaC.
//
// initial_kinematics_of() substitutes a member's exact values into the derivation's momenta and
// angular velocity and evaluates them with GiNaC at 30 digits: tens of microseconds, under the
// process-wide GiNaC lock, and most of a short member's cost in a sweep. Here the same expressions
// are lowered once (lower/lower.hpp) and evaluated for each member in quad precision
// (lower/quad.hpp: 113 bits, more than 30 digits) from the same exact decimals: a few microseconds,
// and no lock. A value the scene wrote as an expression (`theta: pi/2`) is substituted exactly
// before lowering, as GiNaC substitutes it (cos(pi/2) is 0, not 4e-35): the programs are kept for
// each set of such values in effect.
//
// The results, rounded to long double, are initial_kinematics_of()'s (tests/run/test_quad_start.cpp
// compares the two on random members of four models) but for three cases:
//   * a value within ~1e-30 (relative) of a long-double rounding boundary: 1 ulp;
//   * a value that is exactly 0: lowering cancels it exactly, where GiNaC's 30-digit floats leave
//     a residue near 1e-40 in some of its term orders (which change from run to run);
//   * an angle near a zero of its sine or cosine: the decimal rounded to 113 bits is off by up to
//     1e-34, so cos(pi/2 - 2.8e-16) keeps 5e-19 of relative error, a few long-double ulps.
// Rounded to double, the run's precision, they agree in all but about 1 in 1000 of the last case.
// `rotgen bench`, whose long-double references need every bit, keeps initial_kinematics_of().
// Not for linear rotors (run/rotor_chart.hpp), which keep GiNaC.
#pragma once

#include "derive/derive.hpp"
#include "run/kinematics.hpp"
#include "scene/scene.hpp"

#include <array>
#include <map>
#include <memory>
#include <vector>

namespace rotgen {

// A member's numbers: its Euler angles, initial rates (q_dot, p or omega, as the scene's `initial`
// says) and model parameter values.
struct start_values {
    const std::array<double, 3>& angles;
    const std::array<double, 3>& rates;
    const std::vector<double>& parameters;
};

class quad_start {
  public:
    struct programs; // for one set of expression values in effect

    // `scene` gives the written values and the kind of initial rates; both are kept.
    quad_start(const scene_spec& scene, const derivation& d);
    ~quad_start();
    quad_start(const quad_start&) = delete;
    quad_start& operator=(const quad_start&) = delete;

    // Whether quad precision is built in (ROTGEN_HAVE_QUADMATH).
    static bool available();

    // The programs for `v`, lowered on first use; nullptr when they cannot be (a function
    // libquadmath lacks). Call under symbolic_mutex(): lowering uses GiNaC.
    const programs* programs_for(const start_values& v) const;
    // The kinematics of `v` with `p` (from programs_for(v)): no GiNaC, thread-safe.
    initial_kinematics kinematics(const programs& p, const start_values& v) const;

  private:
    const scene_spec& m_scene;
    const derivation& m_d;
    mutable std::map<std::vector<char>, std::unique_ptr<programs>> m_programs;
};

} // namespace rotgen
