// rotgen.sweep: an ensemble in this process, on threads and in SIMD lanes, through the functions
// `rotgen sweep` runs (sweep/members.hpp, sweep/batch.hpp, sweep/parallel.hpp); each member's
// summary row is write_summary_row's text, so the summary is the CLI's summary.csv byte for byte.
// Nothing is written to disk: the rows and samples go to memory, each member to its own slot
// (the CLI's streaming writer and journal are for files). MPI stays the CLI's.
#include "bindings.hpp"

#include "run/lanes.hpp"
#include "run/prepared.hpp"
#include "scene/scene.hpp"
#include "sweep/batch.hpp"
#include "sweep/members.hpp"
#include "sweep/outcome.hpp"
#include "sweep/parallel.hpp"
#include "tune/tune.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>
#include <sstream>

namespace rotgen::python {

namespace {

struct sweep_options {
    std::vector<std::string> vary; // as --vary KEY=...
    unsigned threads = 0;          // 0: every core
    unsigned lanes = 1;
    bool trajectories = true;
};

// The ensemble, prepared once (as sweep.cpp's); what holds GiNaC objects is destroyed under the
// lock.
struct ensemble {
    std::string path;
    std::unique_ptr<scene_spec> scene;
    std::unique_ptr<sweep_plan> plan;
    std::unique_ptr<member_table> table; // refers to *plan
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
        e.scene = std::make_unique<scene_spec>(load_scene(e.path, "sweep"));
    }
    if (e.scene->integrator.method == "auto")
        resolve_released(*e.scene, e.path, text,
                         o.lanes > 1 ? auto_use::lanes : auto_use::ensemble);
    {
        symbolic_scope scope(e.path, text);
        e.plan = std::make_unique<sweep_plan>(read_sweep_plan(*e.scene, o.vary));
        e.table = std::make_unique<member_table>(*e.plan);
        if (o.lanes > 1) lane_check(*e.scene);
        e.prepared = std::make_unique<prepared_scene>(*e.scene, timings);
        if (!o.trajectories) e.prepared->keep_last_row_only();
    }
    interleave_test_hook();
    py::gil_scoped_release released; // compiling locks by itself
    e.prepared->compile_all(timings);
    e.layout = layout_of(*e.prepared);
    if (o.lanes > 1)
        e.lanes = std::make_unique<lane_kernels>(compile_lanes(*e.prepared, timings, o.lanes));
}

// What the members leave: each member's summary row (text) and samples, in its own slot.
struct ensemble_output {
    std::vector<std::string> rows;
    double* samples = nullptr; // [member, sample, trajectory_columns], or null
    std::size_t failed = 0, in_lanes = 0;
    std::uint64_t steps = 0, rhs_evals = 0;
    double seconds = 0; // running the members
};

// Member m's outcome into its slot (called from the pool's threads; the counters under `m`).
void keep(const ensemble& e, std::size_t member, const member_outcome& o, ensemble_output& out,
          std::mutex& m) {
    std::ostringstream row;
    write_summary_row(row, member, e.table->row(member), e.layout, o);
    out.rows[member] = row.str();
    if (out.samples) { // a member that could not start has no samples
        const std::size_t size = e.layout.samples * trajectory_columns(e.layout).size();
        double* to = out.samples + member * size;
        const std::size_t n = std::min(size, o.trajectory.size());
        std::copy(o.trajectory.begin(), o.trajectory.begin() + n, to);
        std::fill(to + n, to + size, std::numeric_limits<double>::quiet_NaN());
    }
    const std::lock_guard<std::mutex> lock(m);
    out.failed += o.ok() ? 0 : 1;
    out.in_lanes += o.in_lanes ? 1 : 0;
    out.steps += o.steps;
    out.rhs_evals += o.rhs_evals;
}

// Every member, in groups of neighbours (a batch of lanes, or one member) taken by the pool's
// threads, with the GIL released; Ctrl-C starts no new group (run_released).
void run_members(const ensemble& e, const sweep_options& o, ensemble_output& out) {
    const member_values base = values_of(e.prepared->scene());
    const sweep_members members{*e.prepared, e.layout,      *e.plan,
                                *e.table,    e.lanes.get(), o.trajectories};
    const std::size_t group = e.lanes ? o.lanes : 1, count = e.table->size();
    const std::size_t groups = (count + group - 1) / group;
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stop{false};
    std::mutex m;
    run_released(
        [&] {
            const auto start = std::chrono::steady_clock::now();
            run_pool(
                o.threads == 0 ? all_cores() : o.threads,
                [&] {
                    const std::size_t g = next++;
                    return stop || g >= groups ? none : g;
                },
                [&](std::size_t g) {
                    const std::size_t first = g * group;
                    const std::vector<member_outcome> done =
                        run_neighbours(members, base, first, std::min(group, count - first));
                    for (std::size_t k = 0; k < done.size(); ++k)
                        keep(e, first + k, done[k], out, m);
                },
                {});
            out.seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        },
        stop);
}

py::dict summary_of(const ensemble& e, const sweep_options& o, const ensemble_output& out) {
    py::dict s;
    s["members"] = e.table->size();
    s["failed"] = out.failed;
    s["in_lanes"] = out.in_lanes;
    s["steps"] = out.steps;
    s["rhs_evals"] = out.rhs_evals;
    s["seconds"] = out.seconds;
    s["threads"] = o.threads == 0 ? all_cores() : o.threads;
    s["lanes"] = e.lanes ? o.lanes : 1u;
    s["arch"] = e.lanes ? e.lanes->arch : std::string();
    return s;
}

py::dict sweep_scene(const std::string& path, const std::string& text, const sweep_options& o) {
    ensemble e(path);
    prepare(e, text, o);
    const std::size_t width = trajectory_columns(e.layout).size();
    ensemble_output out;
    out.rows.resize(e.table->size());
    py::object trajectories = py::none();
    if (o.trajectories) {
        py::array_t<double> a({e.table->size(), e.layout.samples, width});
        out.samples = a.mutable_data();
        trajectories = a;
    }
    run_members(e, o, out);
    std::ostringstream summary;
    write_summary_header(summary, *e.plan, e.layout);
    for (const auto& row : out.rows)
        summary << row;
    py::dict d;
    d["summary_csv"] = summary.str();
    d["columns"] = trajectory_columns(e.layout); // t, the columns, the sensitivities' d(...)
    std::vector<std::string> keys;
    for (const auto& k : e.plan->keys)
        keys.push_back(k.key);
    d["keys"] = keys;
    d["trajectories"] = trajectories;
    d["info"] = summary_of(e, o, out);
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
