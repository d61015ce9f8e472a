// rotgen bench: the answer in scene terms (scene_choice.hpp).
#include "bench/scene_choice.hpp"

#include "bench/sampled_error.hpp"
#include "bench/summary.hpp"
#include "run/engine.hpp"
#include "support/format.hpp"

#include <algorithm>
#include <cmath>

namespace rotgen::bench {

namespace {

// simulate's name of a bench method, or "" for one it does not have.
std::string simulate_method(const std::string& m) {
    if (m == "rodas4") return "rosenbrock";
    for (const char* known :
         {"rk4", "dopri5", "dop853", "implicit_midpoint", "split2", "split4", "split6", "taylor"})
        if (m == known) return m;
    return "";
}

// Whether simulate builds this variant for the scene: specialised and lowered, the Lagrangian
// form's explicit inverse, the body form with the quaternion where the scene needs it.
bool simulate_builds(const variant& v, const scene_spec& scene) {
    if (!v.specialised || !v.lowered) return false;
    if (v.form == form_kind::lagrangian && v.strategy != lagrangian_strategy::explicit_inverse)
        return false;
    return v.form != form_kind::body || v.quaternion || !needs_orientation(scene, false);
}

} // namespace

bool scene_of_row(const result_row& r, const std::vector<variant>& variants,
                  const scene_spec& scene, scene_spec& out) {
    const std::string method = simulate_method(r.method);
    if (r.peer != "rotgen" || r.scalar != "double" || method.empty() ||
        r.variant >= variants.size() || !simulate_builds(variants[r.variant], scene))
        return false;
    out = scene;
    out.form = variants[r.variant].form;
    out.form_given = true;
    out.integrator = integrator_spec{};
    out.integrator.method = method;
    if (r.step > 0)
        out.integrator.step = r.step;
    else
        out.integrator.rtol = out.integrator.atol = r.tol;
    return true;
}

std::string runnable_text(const result_row& r, const std::vector<variant>& variants,
                          const scene_spec& scene) {
    scene_spec s;
    return scene_of_row(r, variants, scene, s) ? "" : "bench only";
}

std::string scene_lines(const scene_spec& s) {
    const integrator_spec& ig = s.integrator;
    std::string line =
        "form: " + std::string(to_string(s.form)) + "\nintegrator: {method: " + ig.method;
    if (ig.fixed_step()) return line + ", step: " + short_number(ig.step, 17) + "}";
    return line + ", rtol: " + short_number(ig.rtol, 6) + ", atol: " + short_number(ig.atol, 6) +
           "}";
}

std::vector<scene_choice> choose_scenes(const std::vector<result_row>& rows,
                                        const std::vector<variant>& variants,
                                        const scene_spec& scene, const std::vector<double>& levels,
                                        double floor, const verify_fn& verify, int tries) {
    std::vector<const result_row*> runnable; // by median time, fastest first
    for (const auto& r : rows) {
        scene_spec s;
        if (r.ok() && std::isfinite(r.median) && !(r.error <= floor_factor * floor) &&
            scene_of_row(r, variants, scene, s))
            runnable.push_back(&r);
    }
    std::stable_sort(
        runnable.begin(), runnable.end(),
        [](const result_row* a, const result_row* b) { return a->median < b->median; });
    std::vector<scene_choice> out;
    for (const double level : levels) {
        scene_choice c;
        c.level = level;
        int tried = 0;
        for (const result_row* r : runnable) {
            if (!(r->error <= level) || tried >= tries) continue;
            ++tried;
            scene_of_row(*r, variants, scene, c.scene);
            const double e = verify(c.scene);
            if (!(e <= level)) {
                c.why += (c.why.empty() ? "" : "; ") + config_name(r) + " measured " +
                         short_number(e) + " when run";
                continue;
            }
            c.row = r, c.verified = e, c.lines = scene_lines(c.scene);
            break;
        }
        if (!c.row && c.why.empty()) c.why = "no configuration simulate runs reached it";
        out.push_back(std::move(c));
    }
    return out;
}

} // namespace rotgen::bench
