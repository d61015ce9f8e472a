// rotgen.sweep: an ensemble in this process, on threads and in SIMD lanes, through the functions
// `rotgen sweep` runs (sweep/members.hpp, sweep/outcome.hpp, sweep/parallel.hpp, run/lanes.hpp);
// the summary is write_summary's text, the same bytes as the CLI's summary.csv. MPI stays the
// CLI's.
#include "bindings.hpp"

#include "run/lanes.hpp"
#include "run/prepared.hpp"
#include "scene/scene.hpp"
#include "sweep/members.hpp"
#include "sweep/outcome.hpp"
#include "sweep/parallel.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

namespace rotgen::python {

namespace {

struct sweep_options {
    std::vector<std::string> vary; // as --vary KEY=...
    unsigned threads = 0;          // 0: every core
    unsigned lanes = 1;
    bool trajectories = true;
};

// The ensemble, prepared once; what holds GiNaC objects is destroyed under the lock.
struct ensemble {
    std::string path;
    std::unique_ptr<scene_spec> scene;
    sweep_plan plan;
    std::vector<std::vector<double>> rows;
    std::unique_ptr<prepared_scene> prepared;
    summary_layout layout;
    std::unique_ptr<lane_kernels> lanes;
    explicit ensemble(std::string p) : path(std::move(p)) {}
    ensemble(const ensemble&) = delete;
    ensemble& operator=(const ensemble&) = delete;
    ~ensemble() {
        symbolic_scope scope(path, "");
        prepared.reset();
        scene.reset();
    }
};

void prepare(ensemble& e, const std::string& text, const sweep_options& o) {
    stage_timings timings;
    {
        symbolic_scope scope(e.path, text);
        e.scene = std::make_unique<scene_spec>(load_scene(e.path));
        e.plan = read_sweep_plan(*e.scene, o.vary);
        e.rows = member_rows(e.plan);
        if (o.lanes > 1) lane_check(*e.scene);
        e.prepared = std::make_unique<prepared_scene>(*e.scene, timings);
    }
    py::gil_scoped_release released; // compiling locks by itself
    e.prepared->compile_all(timings);
    e.layout = layout_of(*e.prepared);
    if (o.lanes > 1) e.lanes = std::make_unique<lane_kernels>(compile_lanes(*e.prepared, timings));
}

// Members first .. first+count-1 in lanes; those a batch cannot carry run alone (as sweep.cpp).
void run_batch(const ensemble& e, const member_values& base, std::size_t first, std::size_t count,
               bool trajectories, std::vector<member_outcome>& outcomes) {
    std::vector<member_values> values;
    for (std::size_t m = first; m < first + count; ++m)
        values.push_back(member_of(e.plan, base, e.rows[m]));
    const std::vector<std::optional<run_result>> results = run_lanes(*e.prepared, *e.lanes, values);
    for (std::size_t k = 0; k < count; ++k)
        outcomes[first + k] = results[k]
                                  ? outcome_of(*e.prepared, e.layout, *results[k], trajectories)
                                  : run_one(*e.prepared, e.layout, values[k], trajectories);
}

// Every member's outcome, in member order, with the GIL released; the calling thread checks for
// Ctrl-C between members (one thread) or about ten times a second (a pool): then no new member
// starts, and the Python error is raised once the members running have finished.
std::vector<member_outcome> run_members(const ensemble& e, const sweep_options& o,
                                        double& seconds) {
    const member_values base = values_of(e.prepared->scene());
    const std::size_t group = e.lanes ? o.lanes : 1;
    const std::size_t groups = (e.rows.size() + group - 1) / group;
    std::vector<member_outcome> outcomes(e.rows.size());
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stop{false};
    signal_check signals;
    {
        py::gil_scoped_release released;
        const auto start = std::chrono::steady_clock::now();
        run_pool(
            o.threads == 0 ? all_cores() : o.threads,
            [&] {
                const std::size_t g = next++;
                return stop || g >= groups ? none : g;
            },
            [&](std::size_t g) {
                if (e.lanes)
                    run_batch(e, base, g * group, std::min(group, e.rows.size() - g * group),
                              o.trajectories, outcomes);
                else
                    outcomes[g] = run_one(*e.prepared, e.layout, member_of(e.plan, base, e.rows[g]),
                                          o.trajectories);
            },
            [&] { stop = stop || (signals.due() && signals.interrupted()); });
        seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    if (stop) throw py::error_already_set();
    return outcomes;
}

// [member, sample, t and the columns]; NaN past a member's last sample (outcome.hpp).
py::array_t<double> trajectories_of(const std::vector<member_outcome>& outcomes,
                                    const summary_layout& layout) {
    const std::size_t width = layout.columns.size() + 1;
    py::array_t<double> a({outcomes.size(), layout.samples, width});
    const std::size_t size = layout.samples * width;
    double* out = a.mutable_data();
    for (const auto& o : outcomes) { // a member that could not start has no samples
        const std::size_t n = std::min(size, o.trajectory.size());
        std::copy(o.trajectory.begin(), o.trajectory.begin() + n, out);
        std::fill(out + n, out + size, std::numeric_limits<double>::quiet_NaN());
        out += size;
    }
    return a;
}

py::dict sweep_scene(const std::string& path, const std::string& text, const sweep_options& o) {
    ensemble e(path);
    prepare(e, text, o);
    double seconds = 0;
    const std::vector<member_outcome> outcomes = run_members(e, o, seconds);
    std::ostringstream summary;
    write_summary(summary, e.plan, e.rows, e.layout, outcomes);
    py::dict d;
    d["summary_csv"] = summary.str();
    std::vector<std::string> columns{"t"};
    columns.insert(columns.end(), e.layout.columns.begin(), e.layout.columns.end());
    d["columns"] = columns;
    std::vector<std::string> keys;
    for (const auto& k : e.plan.keys)
        keys.push_back(k.key);
    d["keys"] = keys;
    d["trajectories"] =
        o.trajectories ? py::object(trajectories_of(outcomes, e.layout)) : py::object(py::none());
    d["seconds"] = seconds;
    d["threads"] = o.threads == 0 ? all_cores() : o.threads;
    d["lanes"] = e.lanes ? o.lanes : 1u;
    d["arch"] = e.lanes ? e.lanes->arch : std::string();
    return d;
}

} // namespace

void init_sweep(py::module_& m) {
    m.def(
        "sweep",
        [](const std::string& path, const std::string& text, std::vector<std::string> vary,
           unsigned threads, unsigned lanes, bool trajectories) {
            return sweep_scene(path, text, {std::move(vary), threads, lanes, trajectories});
        },
        py::arg("path"), py::arg("text"), py::arg("vary"), py::arg("threads"), py::arg("lanes"),
        py::arg("trajectories"));
}

} // namespace rotgen::python
