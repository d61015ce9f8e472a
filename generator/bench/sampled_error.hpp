// rotgen — the one error measure of `rotgen bench`'s choice and of `method: auto` (issue 50): a
// run of a scene against a reference run of it, compared at every sample:
//
//   error = max over the samples of  max( attitude error, |omega - omega_ref| / |omega_ref| )
//
// the attitude error being the rotation angle between the run's and the reference's attitude
// (radians, from the quaternion q0..q3), |omega_ref| the largest |omega_ref| over the samples.
// A form that does not give the attitude (reduced) is compared on its state instead: the angles'
// and rates' largest difference, relative to their largest reference value (at least 1).
#pragma once

#include "run/engine.hpp"
#include "scene/scene.hpp"
#include "support/timings.hpp"

#include <map>
#include <memory>
#include <string>

namespace rotgen::bench {

// The scene recording what the measure compares (q0..q3 and omega1..3, or, where the form gives no
// attitude, the angles and omega).
scene_spec scene_for_error(const scene_spec& scene);

// The measure of `run` against `ref` (both runs of scene_for_error scenes, same samples); NaN when
// the run did not reach the end time or its samples differ.
double sampled_error(const run_result& run, const run_result& ref);

// One run of a scene measured: its error against a reference and its integration time (the
// smallest of `repeats` runs of the prepared scene).
struct measured_run {
    bool ok = false;
    bool refused = false; // the engine refused the scene (user_error): `why` says why
    std::string why;      // a refusal (user_error) or the failed run's message
    double error = 0, seconds = 0;
    run_result result;
};

// Prepared scenes kept across the runs of one scene that differ in their form, method, tolerance
// or step (the tuning's): one preparation (derive, lower, the kernels loaded) per form, method
// and Taylor orders, retuned to each run's tolerance (prepared_scene::retune). Freed under
// GiNaC's lock.
class prepared_scenes {
  public:
    prepared_scenes() = default;
    prepared_scenes(const prepared_scenes&) = delete;
    prepared_scenes& operator=(const prepared_scenes&) = delete;
    ~prepared_scenes();
    // The preparation of `scene`, made on first use and retuned to its integrator.
    prepared_scene& of(const scene_spec& scene, stage_timings& timings);
    std::size_t count() const { return m_kept.size(); } // preparations made
    std::size_t uses() const { return m_uses; }         // runs they served

  private:
    std::map<std::string, std::unique_ptr<prepared_scene>> m_kept;
    std::size_t m_uses = 0;
};

// Runs `scene` (a scene_for_error scene) `repeats` times; a scene the engine refuses is !ok with
// the refusal as `why`. `ref`: null to measure nothing (the reference itself). With `kept`, the
// preparation comes from there (the scene's other fields as in the runs before).
measured_run measure_scene(const scene_spec& scene, const run_result* ref, int repeats,
                           prepared_scenes* kept = nullptr);

// The reference of the measure in the scene's form: the Taylor method at rtol 1e-15, atol 1e-17,
// its floor the measure of a Taylor run at rtol 1e-14, atol 1e-16 against it; where the scene
// refuses the Taylor method (or its runs fail), DOP853 at rtol 1e-14, atol 1e-16, checked at
// 1e-13, 1e-15. Errors up to 3x the floor are the reference's own, and excluded from choices.
// (Measured on the shipped heavy top and free top: Taylor's two runs agree to 6e-14, DOP853's
// rounding leaves it 3e-13 from them at any rtol: a DOP853 reference could not resolve 1e-12.)
struct reference_run {
    run_result result;
    double floor = 0;
    double seconds = 0; // both runs' integration
    std::string method; // the reference's: taylor or dop853
};
reference_run make_reference(const scene_spec& scene);

// Errors at most this many times the reference's floor are at the floor.
inline constexpr double floor_factor = 3;

} // namespace rotgen::bench
