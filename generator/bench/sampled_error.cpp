// rotgen — the one error measure (sampled_error.hpp).
#include "bench/sampled_error.hpp"

#include "run/kernels.hpp"
#include "run/prepared.hpp"
#include "support/error.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>

namespace rotgen::bench {

namespace {

const std::vector<std::string> attitude_records{"q0",     "q1",     "q2",    "q3",
                                                "omega1", "omega2", "omega3"};

// The index in `run.columns` of each name (npos where missing).
std::vector<std::size_t> indices(const run_result& run, const std::vector<std::string>& names) {
    std::vector<std::size_t> at;
    for (const auto& n : names) {
        const auto it = std::find(run.columns.begin(), run.columns.end(), n);
        at.push_back(it == run.columns.end() ? std::string::npos
                                             : std::size_t(it - run.columns.begin()));
    }
    return at;
}

// The rotation angle between two unit quaternions (q0 scalar): 2 atan2(|v|, |w|) of conj(a) b,
// accurate near zero.
double attitude_angle(const double* a, const double* b) {
    const double w = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    const double x = a[0] * b[1] - b[0] * a[1] - (a[2] * b[3] - a[3] * b[2]);
    const double y = a[0] * b[2] - b[0] * a[2] - (a[3] * b[1] - a[1] * b[3]);
    const double z = a[0] * b[3] - b[0] * a[3] - (a[1] * b[2] - a[2] * b[1]);
    return 2 * std::atan2(std::sqrt(x * x + y * y + z * z), std::abs(w));
}

// The largest |omega_ref| over the samples (the scale of the rate error); 1 when it is zero.
double omega_scale(const run_result& ref, const std::vector<std::size_t>& w) {
    double s = 0;
    for (const auto& row : ref.rows)
        s = std::max(s, std::hypot(row[1 + w[0]], row[1 + w[1]], row[1 + w[2]]));
    return s > 0 ? s : 1;
}

// Without the attitude: every column's largest difference relative to its largest reference
// value (at least 1).
double state_error(const run_result& run, const run_result& ref) {
    double e = 0;
    for (std::size_t c = 1; c < ref.rows.front().size(); ++c) {
        double scale = 1;
        for (const auto& row : ref.rows)
            scale = std::max(scale, std::abs(row[c]));
        for (std::size_t i = 0; i < ref.rows.size() && i < run.rows.size(); ++i)
            e = std::max(e, std::abs(run.rows[i][c] - ref.rows[i][c]) / scale);
    }
    return e;
}

} // namespace

scene_spec scene_for_error(const scene_spec& scene) {
    scene_spec s = scene;
    s.record = scene.form == form_kind::reduced || scene.form == form_kind::rotor
                   ? scene.record
                   : attitude_records;
    s.record_default = s.record.empty();
    s.record_where.assign(s.record.size(), scene.where);
    return s;
}

double sampled_error(const run_result& run, const run_result& ref) {
    // a terminal event may end two runs a sample apart: their common samples are compared
    const bool stopped = run.stopped_by >= 0 && ref.stopped_by >= 0;
    if (!run.ok || !ref.ok || (run.rows.size() != ref.rows.size() && !stopped) ||
        ref.rows.empty() || run.rows.empty() || run.columns != ref.columns)
        return NAN;
    const std::size_t n = std::min(run.rows.size(), ref.rows.size());
    const std::vector<std::size_t> at = indices(ref, attitude_records);
    if (std::find(at.begin(), at.end(), std::string::npos) != at.end())
        return state_error(run, ref);
    const std::vector<std::size_t> w{at[4], at[5], at[6]};
    const double scale = omega_scale(ref, w);
    double e = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const auto &a = run.rows[i], &b = ref.rows[i];
        const double qa[4] = {a[1 + at[0]], a[1 + at[1]], a[1 + at[2]], a[1 + at[3]]};
        const double qb[4] = {b[1 + at[0]], b[1 + at[1]], b[1 + at[2]], b[1 + at[3]]};
        const double dw = std::hypot(a[1 + w[0]] - b[1 + w[0]], a[1 + w[1]] - b[1 + w[1]],
                                     a[1 + w[2]] - b[1 + w[2]]);
        if (std::isnan(dw) || std::isnan(qa[0])) return NAN;
        e = std::max({e, attitude_angle(qa, qb), dw / scale});
    }
    return e;
}

prepared_scenes::~prepared_scenes() {
    const std::lock_guard<std::mutex> lock(symbolic_mutex());
    m_kept.clear();
}

prepared_scene& prepared_scenes::of(const scene_spec& scene, stage_timings& timings) {
    const integrator_spec& ig = scene.integrator;
    const std::string key = std::string(to_string(scene.form)) + " " + ig.method +
                            (ig.method == "taylor" ? " " + taylor_call(ig) : "");
    auto it = m_kept.find(key);
    if (it == m_kept.end()) {
        // GiNaC under the lock (Python's other threads), as run_member uses it
        const std::lock_guard<std::mutex> lock(symbolic_mutex());
        it = m_kept.emplace(key, std::make_unique<prepared_scene>(scene, timings)).first;
    }
    it->second->retune(ig);
    ++m_uses;
    return *it->second;
}

measured_run measure_scene(const scene_spec& scene, const run_result* ref, int repeats,
                           prepared_scenes* kept) {
    measured_run m;
    try {
        stage_timings timings;
        prepared_scenes own;
        prepared_scene& prepared = (kept ? *kept : own).of(scene, timings);
        const member_values values = values_of(scene);
        m.seconds = INFINITY;
        for (int k = 0; k < repeats; ++k) {
            m.result = run_member(prepared, values, timings);
            m.seconds = std::min(m.seconds, m.result.integrate_seconds);
            if (!m.result.ok) break;
        }
    } catch (const user_error& e) {
        m.why = e.message();
        m.refused = true;
        return m;
    }
    m.ok = m.result.ok;
    if (!m.ok) m.why = m.result.message;
    m.error = ref ? sampled_error(m.result, *ref) : 0;
    if (m.ok && !std::isfinite(m.error)) m.ok = false, m.why = "its samples differ";
    return m;
}

namespace {

// The reference by `method` at `tight` and its floor from a run at `loose` (atol 100x below each);
// !ok where the scene refuses the method or either run fails.
bool try_reference(const scene_spec& scene, const std::string& method, double tight, double loose,
                   reference_run& r, std::string& why) {
    scene_spec s = scene_for_error(scene);
    s.integrator = integrator_spec{};
    s.integrator.method = method;
    s.integrator.rtol = tight, s.integrator.atol = tight * 1e-2;
    s.integrator.max_steps = 100'000'000;
    measured_run ref = measure_scene(s, nullptr, 1);
    why = ref.why;
    if (!ref.ok) return false;
    s.integrator.rtol = loose, s.integrator.atol = loose * 1e-2;
    const measured_run check = measure_scene(s, &ref.result, 1);
    if (!check.ok || !std::isfinite(check.error)) return false;
    r.floor = check.error;
    r.seconds = ref.seconds + check.seconds;
    r.result = std::move(ref.result);
    r.method = method;
    return true;
}

} // namespace

reference_run make_reference(const scene_spec& scene) {
    reference_run r;
    std::string why;
    if (try_reference(scene, "taylor", 1e-15, 1e-14, r, why)) return r;
    if (try_reference(scene, "dop853", 1e-14, 1e-13, r, why)) return r;
    throw user_error(scene.integrator_where,
                     "the reference run (dop853 rtol 1e-14) failed: " + why);
}

} // namespace rotgen::bench
