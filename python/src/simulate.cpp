// rotgen.simulate: one scene through the run engine (run/engine.hpp), as `rotgen simulate` runs
// it, the samples returned as NumPy arrays instead of written to a CSV.
#include "bindings.hpp"

#include "run/engine.hpp"
#include "run/prepared.hpp"
#include "scene/scene.hpp"
#include "support/format.hpp"
#include "support/memory_files.hpp"
#include "tune/tune.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>

namespace rotgen::python {

namespace {

// What holds GiNaC objects, destroyed under the lock.
struct prepared_run {
    std::string path, text;
    std::unique_ptr<scene_spec> scene;
    std::unique_ptr<prepared_scene> prepared;
    prepared_run(const prepared_run&) = delete;
    prepared_run& operator=(const prepared_run&) = delete;
    prepared_run(std::string p, std::string t) : path(std::move(p)), text(std::move(t)) {}
    ~prepared_run() {
        symbolic_scope scope(path, "");
        prepared.reset();
        scene.reset();
    }
};

// rows (t, then the columns) as one array; the result's t and y are views of it.
py::array_t<double> rows_array(const std::vector<std::vector<double>>& rows, std::size_t width) {
    py::array_t<double> a({rows.size(), width});
    auto w = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t j = 0; j < width; ++j)
            w(i, j) = rows[i][j];
    return a;
}

py::dict summary_of(const scene_spec& scene, const run_result& r) {
    py::dict s;
    s["model"] = scene.model.name;
    s["form"] = std::string(to_string(scene.form));
    s["state_size"] = r.state_size;
    s["method"] = scene.integrator.method;
    s["auto"] = scene.integrator.auto_choice; // method auto: what tune/ chose ("" otherwise)
    s["steps"] = r.stats.accepted;
    s["rejected"] = r.stats.rejected;
    s["rhs_evals"] = r.stats.rhs_evals;
    s["jac_evals"] = r.stats.jac_evals;
    s["factorisations"] = r.stats.factorisations;
    py::dict drifts;
    for (const auto& inv : r.invariants)
        drifts[py::str(inv.what.name)] = inv.drift;
    s["drifts"] = drifts;
    s["chart"] = r.chart_note;
    s["integrate_seconds"] = r.integrate_seconds;
    s["kernels_cached"] = r.kernels_cached;
    s["t_reached"] = r.t_reached; // the end time, a terminal event's, or where a run stopped
    return s;
}

// With sensitivities: the keys, the d(...) columns' names, and per row the d(...) values
// (rows x sensitivity columns) and S (rows x n x k).
void add_sensitivities(py::dict& d, const run_result& r) {
    d["sensitivity_keys"] = r.sensitivity_keys;
    d["sensitivity_columns"] = r.sensitivity_columns;
    const std::size_t rows = r.sensitivity_rows.size(), k = r.sensitivity_keys.size();
    py::array_t<double> values({rows, r.sensitivity_columns.size()});
    py::array_t<double> S({rows, k == 0 ? 0 : r.state_size, k});
    auto v = values.mutable_unchecked<2>();
    auto s = S.mutable_unchecked<3>();
    for (std::size_t i = 0; i < rows; ++i) {
        for (std::size_t j = 0; j < r.sensitivity_columns.size(); ++j)
            v(i, j) = r.sensitivity_rows[i][j];
        for (std::size_t a = 0; k > 0 && a < r.state_size; ++a)
            for (std::size_t b = 0; b < k; ++b)
                s(i, a, b) = r.state_sensitivities[i][a * k + b];
    }
    d["sensitivity_values"] = values;
    d["state_sensitivities"] = S;
}

py::dict result_of(const scene_spec& scene, const run_result& r) {
    py::dict d;
    add_sensitivities(d, r);
    d["rows"] = rows_array(r.rows, r.columns.size() + 1);
    d["columns"] = r.columns;
    py::list events;
    for (std::size_t k = 0; k < r.event_rows.size(); ++k) {
        const std::vector<double>& row = r.event_rows[k];
        py::array_t<double> values(row.size() - 1, row.data() + 1);
        events.append(
            py::make_tuple(r.event_names[r.event_index[k]], row[0], r.event_phase[k], values));
    }
    d["events"] = events;
    d["event_names"] = r.event_names;
    d["summary"] = summary_of(scene, r);
    d["ok"] = r.ok;
    // the CLI's line for a run that stopped (simulate.cpp), without the partial file
    const double t = r.t_reached; // past the last row when the run stopped between samples
    d["message"] = r.ok ? std::string()
                        : to_string(scene.integrator_where) +
                              ": the run stopped at t = " + format_double(t) + " of " +
                              format_double(scene.t_end) + ": " + r.message;
    return d;
}

// Reads and prepares the scene (under the lock), as `rotgen simulate` does (run_scene), then runs
// it with the GIL released; Ctrl-C stops it at the next sample (run_released).
py::dict simulate_scene(const std::string& path, const std::string& text) {
    prepared_run run(path, text);
    stage_timings timings;
    {
        symbolic_scope scope(path, text);
        run.scene = std::make_unique<scene_spec>(load_scene(path, "simulate"));
    }
    if (run.scene->integrator.method == "auto")
        resolve_released(*run.scene, path, text, auto_use::single_run);
    {
        symbolic_scope scope(path, text);
        run.prepared = std::make_unique<prepared_scene>(*run.scene, timings);
    }
    interleave_test_hook();
    struct interrupted {};
    std::atomic<bool> stop{false};
    run_result r;
    run_released(
        [&] {
            r = run_member(*run.prepared, values_of(*run.scene), timings, [&](double) {
                if (stop) throw interrupted{};
            });
        },
        stop);
    return result_of(*run.scene, r);
}

// The scene read and checked (as `rotgen simulate` reads it): what it runs.
py::dict scene_info(const std::string& path, const std::string& text) {
    std::string model, model_file, form, method;
    double t_start = 0, t_end = 0;
    long samples = 0;
    std::vector<std::string> record, events;
    {
        symbolic_scope scope(path, text); // no Python object is touched in here
        const scene_spec scene = load_scene(path, "simulate");
        model = scene.model.name;
        model_file = scene.model.file;
        form = to_string(scene.form);
        method = scene.integrator.method;
        t_start = scene.t_start, t_end = scene.t_end, samples = scene.samples;
        record = scene.record;
        for (const auto& e : scene.events)
            events.push_back(e.name);
    }
    py::dict d;
    d["model"] = model;
    d["model_file"] = model_file;
    d["form"] = form;
    d["method"] = method;
    d["t_start"] = t_start;
    d["t_end"] = t_end;
    d["samples"] = samples;
    d["record"] = record;
    d["events"] = events;
    return d;
}

} // namespace

// Method auto resolved (tune/) with the GIL released and without the lock, which the tuning runs
// take as they need it (run_member); the scene's text is registered for the cache key.
void resolve_released(scene_spec& scene, const std::string& path, const std::string& text,
                      auto_use use) {
    py::gil_scoped_release released;
    if (!text.empty()) set_memory_file(path, text);
    try {
        resolve_auto(scene, nullptr, use);
    } catch (...) {
        if (!text.empty()) erase_memory_file(path);
        throw;
    }
    if (!text.empty()) erase_memory_file(path);
}

void init_simulate(py::module_& m) {
    m.def("simulate", &simulate_scene, py::arg("path"), py::arg("text") = "");
    m.def("scene_info", &scene_info, py::arg("path"), py::arg("text") = "");
}

} // namespace rotgen::python
