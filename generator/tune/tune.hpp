// rotgen — `method: auto` and `rotgen tune` (issue 50): the integrator a scene runs fastest with
// at a given error, chosen by measuring the scene itself.
//
//   integrator: {method: auto, error: 1e-8}   # the largest error accepted at the samples
//
// The choice: for each candidate form (the scene's `form:` when it gives one, else its default and
// the body form) and each method that accepts the scene (dop853, dopri5, taylor, split2/4/6: a
// method the engine refuses for this scene — its model, its form, its features — is left out),
// the loosest tolerance (rtol = atol, as the bench's rows, on a half-decade grid) whose run meets
// `error` under the bench's one measure (bench/sampled_error.hpp) against a tight reference, on the
// scene's whole span; for DOP853 also the fewest fixed steps (span / n, n on a quarter-octave grid
// from the adaptive run's step count) whose run meets it, where the choice is for one run (an
// ensemble's members move otherwise: auto_use); then, among those, the fastest (the smallest of
// three timed runs). Errors at
// the reference's floor are not trusted: a target below it is refused, as is one that no
// configuration reaches (user_error naming the smallest error reached).
//
// The choice is cached in <cache_directory()>/tune/<key>.choice, the key a hash of the content
// of the scene and of its model (not their paths), the target, the compiler and this procedure's
// version; another machine (or compiler) may choose otherwise.
#pragma once

#include "forms/form_kind.hpp"
#include "scene/scene.hpp"

#include <iosfwd>
#include <string>
#include <vector>

namespace rotgen {

// What the choice is for: one run (simulate, tune, Python's simulate) may take fixed steps, an
// ensemble (sweep) only steps under error control, which follow each member's own motion, and an
// ensemble in SIMD lanes (sweep --lanes) only the methods the lanes run (dop853, taylor).
enum class auto_use : int { single_run, ensemble, lanes };

struct auto_choice {
    std::string method;
    double rtol = 0, atol = 0;
    double step = 0; // > 0: DOP853 with this fixed step (no rtol, atol)
    form_kind form = form_kind::lagrangian;
    double error = 0;        // its measured error (the one measure) on the tuning span
    double run_seconds = 0;  // its integration time
    double floor = 0;        // the reference's floor
    double tune_seconds = 0; // what choosing it cost (the tuning run, when first made)
    bool cached = false;     // read from the cache
};

// "dop853 rtol 3e-09 atol 3e-09 in the body form", "dop853 step 0.392157 in the body form".
std::string choice_text(const auto_choice& c);

// The choice for `scene` (method auto, target scene.integrator.error), measured now (no cache).
// `log`: one line per measured configuration, or null. Throws user_error as described above.
auto_choice tune_scene(const scene_spec& scene, std::ostream* log,
                       auto_use use = auto_use::single_run);

// The methods `tune_scene` may choose from for this scene: those the engine accepts for it in
// one of its candidate forms ("dop853", "split4", ...).
std::vector<std::string> methods_accepting(const scene_spec& scene);

// The cache key of a scene with method auto (hex): its text and its model's, the target, the
// compiler's identity, the tuning procedure's version and the use.
std::string auto_cache_key(const scene_spec& scene, auto_use use = auto_use::single_run);

// `scene` with method auto resolved (from the cache, or tuned and cached): the method, rtol, atol,
// the form (unless the scene gave one) and integrator.auto_choice, the line the summaries print
// after "auto: ". Scenes of other methods are left as they are (and the choice returned is empty).
// `log` as in tune_scene.
auto_choice resolve_auto(scene_spec& scene, std::ostream* log = nullptr,
                         auto_use use = auto_use::single_run);

} // namespace rotgen
