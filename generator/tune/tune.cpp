// rotgen — `method: auto`: the search (tune.hpp).
#include "tune/tune.hpp"

#include "bench/sampled_error.hpp"
#include "run/lanes.hpp"
#include "scene/sensitivities.hpp"
#include "support/error.hpp"
#include "support/format.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <ostream>

namespace rotgen {

namespace {

// The tolerances tried: 1e-2, 3e-3, 1e-3, ..., 1e-14 (index j: 1e-2 / sqrt(10)^j, rounded to
// one significant digit, 1 or 3).
double grid_tolerance(int j) {
    const int k = 2 + j / 2;
    return (j % 2 == 0 ? 1.0 : 0.3) * std::pow(10.0, -k);
}
constexpr int grid_size = 25; // 1e-2 .. 1e-14

// The grid index nearest `tol`.
int grid_index(double tol) {
    const int j = int(std::lround(-2 * std::log10(tol / 1e-2)));
    return std::clamp(j, 0, grid_size - 1);
}

const std::vector<std::string> auto_methods{"dop853", "dopri5", "taylor",
                                            "split2", "split4", "split6"};

// The methods auto may choose for this scene: those that integrate its sensitivities, if it has
// any, and for lanes those the lanes run (run/lanes.hpp).
std::vector<std::string> methods_for(const scene_spec& scene, auto_use use = auto_use::single_run) {
    std::vector<std::string> r;
    for (const auto& m : auto_methods)
        if ((!scene.sensitivities.active() || method_takes_sensitivities(m)) &&
            (use != auto_use::lanes || lanes_run(m)))
            r.push_back(m);
    return r;
}

bool is_split(const std::string& m) {
    return m.rfind("split", 0) == 0;
}

// The forms a choice may use: the scene's when it gives one (or a rotor's one form), else the
// scene's default and the body form.
std::vector<form_kind> candidate_forms(const scene_spec& scene) {
    if (scene.form_given || scene.model.rotor || scene.form == form_kind::body) return {scene.form};
    return {scene.form, form_kind::body};
}

struct candidate {
    std::string method;
    form_kind form;
    double tol = 0;
    bench::measured_run run;
    double step = 0; // > 0: fixed steps of this size (tol unused)
};

scene_spec configured(const scene_spec& base, form_kind form, const std::string& method, double tol,
                      double step = 0) {
    scene_spec s = base;
    s.form = form;
    s.integrator = integrator_spec{};
    s.integrator.method = method;
    if (step > 0)
        s.integrator.step = step;
    else
        s.integrator.rtol = s.integrator.atol = tol; // as a bench row at tol
    return s;
}

scene_spec configured(const scene_spec& base, const candidate& c) {
    return configured(base, c.form, c.method, c.tol, c.step);
}

// The log line of one measured configuration: "  tune    dop853 body rtol 1e-08: error 2.6e-09".
void log_try(std::ostream* log, const candidate& c) {
    if (!log) return;
    *log << "  tune    " << c.method << " " << to_string(c.form)
         << (c.step > 0 ? " step " + short_number(c.step, 6) : " rtol " + short_number(c.tol))
         << ": " << (c.run.ok ? "error " + short_number(c.run.error) : c.run.why) << "\n";
}

bool meets(const candidate& c, double target) {
    return c.run.ok && c.run.error <= target;
}

// A method in a form: the loosest grid tolerance that meets the target (run once each), or the
// refusal / the most accurate run it made (!meets).
struct search_result {
    candidate best; // meets: the loosest that meets; else the most accurate
    bool meets = false, refused = false;
};

search_result search(const scene_spec& base, form_kind form, const std::string& method,
                     const run_result& ref, double target, bench::prepared_scenes& kept,
                     std::ostream* log) {
    search_result r;
    const auto try_at = [&](int j) {
        candidate c{method, form, grid_tolerance(j), {}};
        c.run = bench::measure_scene(configured(base, c), &ref, 1, &kept);
        log_try(log, c);
        return c;
    };
    int j = grid_index(target);
    candidate c = try_at(j);
    if (c.run.refused) {
        r.refused = true;
        r.best = c;
        return r;
    }
    if (meets(c, target)) { // looser while it still meets
        r.meets = true, r.best = c;
        while (j > 0 && meets(c = try_at(--j), target))
            r.best = c;
        return r;
    }
    r.best = c;
    while (j < grid_size - 1) { // tighter, by the error's excess (a half decade at least)
        const double excess = c.run.ok ? c.run.error / target : 10;
        j = std::min(grid_size - 1, j + std::clamp(int(std::ceil(std::log10(excess) * 2)), 1, 6));
        c = try_at(j);
        if (c.run.ok && (!r.best.run.ok || c.run.error < r.best.run.error)) r.best = c;
        if (meets(c, target)) return r.meets = true, r;
    }
    return r;
}

// DOP853 with n fixed steps over the span, as the bench's `dop853 fixed` rows (no error control:
// cheaper per step where the motion's time scale is steady): the fewest n on a quarter-octave grid
// around `adaptive`'s step count whose run meets the target, or none within 4x that count.
std::optional<candidate> fixed_search(const scene_spec& base, const candidate& adaptive,
                                      const run_result& ref, double target,
                                      bench::prepared_scenes& kept, std::ostream* log) {
    const double span = std::abs(base.t_end - base.t_start);
    const double n0 = double(std::max<std::size_t>(adaptive.run.result.stats.steps, 1));
    const auto try_at = [&](int j) { // n = ceil(n0 2^(j/4)) steps
        candidate c{adaptive.method, adaptive.form, 0, {}};
        c.step = span / std::ceil(n0 * std::exp2(j / 4.0) - 1e-9);
        c.run = bench::measure_scene(configured(base, c), &ref, 1, &kept);
        log_try(log, c);
        return c;
    };
    int j = 0;
    candidate c = try_at(j);
    if (meets(c, target)) { // fewer steps while it still meets
        candidate best = c;
        while (span / best.step > 1 && meets(c = try_at(--j), target))
            best = c;
        return best;
    }
    while (j < 8)
        if (meets(c = try_at(++j), target)) return c;
    return std::nullopt;
}

} // namespace

std::string choice_text(const auto_choice& c) {
    const std::string how = c.step > 0
                                ? " step " + short_number(c.step, 6)
                                : " rtol " + short_number(c.rtol) + " atol " + short_number(c.atol);
    return c.method + how + " in the " + to_string(c.form) + " form";
}

std::vector<std::string> methods_accepting(const scene_spec& scene) {
    std::vector<std::string> ok;
    for (const auto& m : methods_for(scene))
        for (const form_kind f : candidate_forms(scene)) {
            if (is_split(m) && f != form_kind::body && scene.form_given) continue;
            scene_spec s = bench::scene_for_error(configured(scene, f, m, 1e-6));
            s.t_end = s.t_start + (scene.t_end - scene.t_start) * 1e-3; // a short run suffices
            if (bench::measure_scene(s, nullptr, 1).ok) {
                ok.push_back(m);
                break;
            }
        }
    return ok;
}

auto_choice tune_scene(const scene_spec& scene, std::ostream* log, auto_use use) {
    const auto t0 = std::chrono::steady_clock::now();
    const double target = scene.integrator.error;
    const bench::reference_run ref = bench::make_reference(scene);
    if (!(target > bench::floor_factor * ref.floor))
        throw user_error(scene.integrator_where,
                         "integrator auto: error " + short_number(target) +
                             " is below what the tuning reference resolves (" +
                             short_number(bench::floor_factor * ref.floor) +
                             ", 3x its own error); the smallest error reached is " +
                             short_number(bench::floor_factor * ref.floor));
    const scene_spec base = bench::scene_for_error(scene);
    bench::prepared_scenes kept; // every candidate is `base` with its form and integrator
    std::vector<candidate> found;
    candidate closest{"", scene.form, 0, {}};
    for (const form_kind f : candidate_forms(scene))
        for (const auto& m : methods_for(scene, use)) {
            if (is_split(m) && f != form_kind::body) continue; // they run the body form
            search_result s = search(base, f, m, ref.result, target, kept, log);
            if (s.refused) continue;
            if (s.meets) found.push_back(s.best);
            if (s.meets && m == "dop853" && use == auto_use::single_run)
                if (auto fixed = fixed_search(base, s.best, ref.result, target, kept, log))
                    found.push_back(*fixed);
            if (s.best.run.ok && (closest.method.empty() || s.best.run.error < closest.run.error))
                closest = s.best;
        }
    if (found.empty())
        throw user_error(scene.integrator_where,
                         "integrator auto: no configuration reaches error " + short_number(target) +
                             "; the smallest error reached is " +
                             (closest.method.empty()
                                  ? std::string("none (every method failed)")
                                  : short_number(closest.run.error) + " (" + closest.method +
                                        " rtol " + short_number(closest.tol) + ")"));
    for (candidate& c : found) // timed again: the smallest of three runs
        c.run.seconds = bench::measure_scene(configured(base, c), &ref.result, 3, &kept).seconds;
    if (log)
        *log << "  tune    " << kept.uses() << " runs on " << kept.count()
             << " preparations (derivation and kernels, one per form, method and Taylor order)\n";
    const candidate& best =
        *std::min_element(found.begin(), found.end(), [](const candidate& a, const candidate& b) {
            return a.run.seconds < b.run.seconds;
        });
    auto_choice choice;
    choice.method = best.method, choice.rtol = best.tol, choice.atol = best.tol;
    choice.step = best.step;
    choice.form = is_split(best.method) ? form_kind::body : best.form;
    choice.error = best.run.error, choice.run_seconds = best.run.seconds;
    choice.floor = ref.floor;
    choice.tune_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return choice;
}

} // namespace rotgen
