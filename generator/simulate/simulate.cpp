#include "simulate/simulate.hpp"

#include "run/continue_from.hpp"
#include "run/engine.hpp"
#include "run/provenance.hpp"
#include "scene/scene.hpp"
#include "simulate/figures.hpp"
#include "simulate/plot.hpp"
#include "support/atomic_file.hpp"
#include "support/error.hpp"
#include "support/format.hpp"
#include "support/output_paths.hpp"
#include "support/progress.hpp"
#include "support/standard_output.hpp"
#include "support/timings.hpp"
#include "view/view.hpp"

#include <cmath>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

namespace rotgen {

namespace {

// Each row, then its sensitivity columns `more[k]` where there are (run_result).
void write_rows(std::ostream& os, const std::vector<std::vector<double>>& rows,
                const std::vector<std::vector<double>>& more = {}) {
    for (std::size_t k = 0; k < rows.size(); ++k) {
        const auto& row = rows[k];
        for (std::size_t i = 0; i < row.size(); ++i)
            os << (i ? "," : "") << format_number(row[i]);
        if (k < more.size())
            for (double v : more[k])
                os << "," << format_number(v);
        os << "\n";
    }
}

// The CSV's first line: which rotgen, model and form made it (run/provenance.hpp).
std::string provenance(const scene_spec& scene) {
    return provenance_line(provenance_of(scene.model, scene.form));
}

// The samples, handed to `outputs`.
void write_csv(atomic_file& out, const scene_spec& scene, const run_result& r,
               output_set& outputs) {
    std::ostream& os = out.stream();
    os << provenance(scene) << "\nt";
    for (const auto& c : r.columns)
        os << "," << c;
    for (const auto& c : r.sensitivity_columns)
        os << "," << c;
    os << "\n";
    write_rows(os, r.rows, r.sensitivity_rows);
    out.commit(outputs);
}

// One row per event in time order: its name, t, the recorded columns at the event.
void write_events(atomic_file& out, const scene_spec& scene, const run_result& r,
                  output_set& outputs) {
    std::ostream& os = out.stream();
    os << provenance(scene) << "\nevent,t";
    for (const auto& c : r.columns)
        os << "," << c;
    os << "\n";
    for (std::size_t k = 0; k < r.event_rows.size(); ++k) {
        os << r.event_names[r.event_index[k]];
        for (double v : r.event_rows[k])
            os << "," << format_number(v);
        os << "\n";
    }
    out.commit(outputs);
}

// Where a pair of zeros of event i may hide (g neither changes sign nor stays away from 0 there).
void print_event_doubts(std::ostream& os, const run_result& r, std::size_t i) {
    std::size_t n = 0;
    const run_result::event_doubt* first = nullptr;
    for (const auto& d : r.event_doubts)
        if (d.index == i && n++ == 0) first = &d;
    if (n == 0) return;
    os << "  warning event " << r.event_names[i]
       << ": a pair of zeros may hide in t = " << format_double(first->from) << " .. "
       << format_double(first->to)
       << (n == 1 ? "" : " and " + std::to_string(n - 1) + " more intervals")
       << " (g neither changes sign nor stays away from 0 there)\n";
}

// How many times each event occurred, and which one stopped the run.
void print_events(std::ostream& os, const run_result& r) {
    for (std::size_t i = 0; i < r.event_names.size(); ++i) {
        std::size_t n = 0;
        for (std::size_t k : r.event_index)
            n += k == i ? 1 : 0;
        os << "  event   " << r.event_names[i] << ": " << n << (n == 1 ? " time" : " times");
        if (r.stopped_by == static_cast<int>(i))
            os << "; stopped the run at t = " << format_double(r.rows.back()[0]);
        os << "\n";
        print_event_doubts(os, r, i);
    }
}

// max |v(t) - v(0)| over the samples and, for a run that stopped between samples, the state it
// stopped at; relative to |v(0)| unless v starts near 0 (below 1e-9 of its largest value along
// the run): a relative drift of a momentum that starts at 0 means nothing.
void print_invariants(std::ostream& os, const run_result& r) {
    for (const auto& inv : r.invariants) {
        const std::string& name = inv.what.name;
        const bool conserved = inv.what.conserved;
        const bool near_zero =
            std::abs(inv.first) <= 1e-9 * inv.largest || std::abs(inv.first) < 1e-300;
        os << "  " << (conserved ? "drift   " : "change  ") << name << ": max |" << name << "(t) - "
           << name << "(0)| = " << short_number(inv.drift)
           << (near_zero ? " (absolute: " + name + "(0) is near 0)"
                         : " (relative " + short_number(inv.drift / std::abs(inv.first)) + ")")
           << (conserved ? "" : ", not conserved: the model is damped or driven") << "\n";
    }
    std::size_t non_finite = 0;
    for (const auto& row : r.rows)
        for (double v : row)
            non_finite += std::isfinite(v) ? 0 : 1;
    if (non_finite > 0)
        os << "  note    " << non_finite << " recorded values are not finite (inf or nan): "
           << "Euler-angle rates are undefined at theta = 0 and pi\n";
}

void print_summary(std::ostream& os, const simulate_request& q, const scene_spec& scene,
                   const run_result& r, const stage_timings& timings) {
    const integrator_spec& ig = scene.integrator;
    const double prepare = timings.total("derive") + timings.total("forms");
    const double compile =
        timings.total("lower") + timings.total("emit") + timings.total("compile");
    os << "rotgen simulate " << q.scene << "\n"
       << "  model   " << scene.model.name << " (" << scene.model.file << "), " << to_string(r.form)
       << " form, " << r.state_size << " states\n";
    if (scene.from)
        os << "  start   from the last row of " << scene.from->file << " (line " << scene.from->line
           << "), t = " << format_double(scene.t_start) << "\n";
    if (!r.chart_note.empty()) os << "  chart   " << r.chart_note << "\n";
    os << "  method  " << ig.method;
    if (ig.fixed_step())
        os << " step " << format_double(ig.step);
    else
        os << " rtol " << format_double(ig.rtol) << " atol " << format_double(ig.atol);
    // the span the steps covered: a run that stopped between samples went past its last row
    const double last_row = r.rows.empty() ? scene.t_start : r.rows.back()[0];
    os << ", t " << format_double(scene.t_start) << " .. " << format_double(r.t_reached);
    if (r.t_reached != last_row)
        os << " (stopped there; the last sample is at t = " << format_double(last_row) << ")";
    os << "\n"
       << "  steps   " << r.stats.accepted << " accepted, " << r.stats.rejected << " rejected; "
       << r.stats.rhs_evals << " RHS and " << r.stats.jac_evals << " Jacobian evaluations, "
       << r.stats.factorisations << " factorisations\n"
       << "  time    " << format_duration(r.integrate_seconds) << " integrating; "
       << format_duration(prepare) << " deriving, " << format_duration(compile) << " "
       << (r.kernels_cached ? "emitting and loading the cached kernels"
                            : "emitting and compiling the kernels")
       << "\n";
    print_invariants(os, r);
    print_events(os, r);
}

// The plot, from the CSV written (its temporary, `csv`), or from a scratch CSV beside the PNG when
// the CSV is a stream; it appears with `outputs`.
void draw_plot(const simulate_request& q, std::string csv, const scene_spec& scene,
               const run_result& r, output_set& outputs) {
    std::optional<atomic_file> scratch;
    if (csv.empty()) { // a stream cannot be read back
        scratch.emplace(q.plot + ".csv");
        write_rows(scratch->stream(), r.rows);
        scratch->stream().flush();
        csv = scratch->temporary();
    }
    // The energy and the conserved momenta are drawn as their drift from the first sample.
    std::map<std::string, double> drifts;
    for (const auto& inv : r.invariants)
        for (std::size_t i = 0; i < r.columns.size(); ++i)
            if (r.columns[i] == inv.what.name && !r.rows.empty() &&
                (inv.what.conserved || inv.what.name == "energy"))
                drifts[inv.what.name] = r.rows[0][i + 1];
    plot_run(q.plot, csv, r.record,
             scene.model.name + " (" + to_string(r.form) + " form, " + scene.integrator.method +
                 ")",
             drifts, &outputs);
}

// Where the samples go: the requested file, "-" for standard output, or by default
// <scene name>.csv in the current folder.
std::string default_csv(const std::string& scene) {
    std::string stem = scene.substr(scene.find_last_of('/') + 1);
    if (const auto dot = stem.rfind('.'); dot != std::string::npos && dot > 0) stem.erase(dot);
    return stem + ".csv";
}

std::string csv_path(const simulate_request& q) {
    return q.csv.empty() ? default_csv(q.scene) : q.csv;
}

// Every file one run may write, named before any work. Sibling names derive from the output's
// stem, or from the scene's name (in the current folder) when the output is a stream: "-", a
// device, a FIFO.
struct run_files {
    std::string csv, events, partial, partial_events; // events: empty when none
};

run_files files_of(const simulate_request& q, const scene_spec& scene) {
    run_files f;
    f.csv = csv_path(q);
    std::string base = is_stream_output(f.csv) ? default_csv(q.scene) : f.csv;
    if (base.size() > 4 && base.compare(base.size() - 4, 4, ".csv") == 0)
        base.erase(base.size() - 4);
    if (!q.events.empty())
        f.events = q.events;
    else if (!scene.events.empty())
        f.events = base + ".events.csv";
    f.partial = base + ".partial.csv";
    if (!f.events.empty()) f.partial_events = base + ".partial.events.csv";
    return f;
}

// Refuses (exit 2) two outputs that are one file, or an output that is an input.
void check_files(const simulate_request& q, const scene_spec& scene, const run_files& f) {
    std::vector<named_file> outputs{{f.csv, q.csv.empty() ? "the default output" : "-o"}};
    if (!f.events.empty())
        outputs.push_back({f.events, q.events.empty() ? "the events file" : "--events"});
    if (!q.plot.empty()) outputs.push_back({q.plot, "--plot"});
    if (!q.view.empty()) outputs.push_back({q.view, "--view"});
    for (const auto& [file, kind] : {std::pair{q.plot_axis, "axis"}, {q.plot_polhode, "polhode"}})
        if (!file.empty()) {
            outputs.push_back({file, std::string("--plot-") + kind});
            outputs.push_back(
                {figure_data_path(file, kind), std::string("--plot-") + kind + "'s data"});
        }
    outputs.push_back({f.partial, "the partial rows' file (exit 3)"});
    if (!f.partial_events.empty())
        outputs.push_back({f.partial_events, "the partial events' file (exit 3)"});
    std::vector<named_file> inputs{{q.scene, "the scene"}, {scene.model.file, "the model"}};
    if (!q.from.empty()) inputs.push_back({q.from, "--from"});
    check_distinct_files(outputs, inputs);
}

// Standard output and devices first (they cannot be renamed), then the summary (on standard
// output: checked), then the files: exit 2 leaves no file.
void commit_outputs(output_set& outputs, const std::string& summary, const simulate_request& q,
                    const std::string& csv) {
    outputs.commit_streams();
    if (!q.quiet && is_standard_output(csv)) {
        std::cerr << summary;
    } else if (!q.quiet) {
        std::cout << summary;
        flush_standard_output();
    }
    outputs.commit_files();
}

// A run that could not finish: the rows so far go to <output stem>.partial.csv (never under the
// requested name), its events to <output stem>.partial.events.csv; exit status 3.
int report_partial(const std::vector<std::string>& inputs, const run_files& f,
                   const simulate_request& q, const scene_spec& scene, const run_result& r,
                   std::ostringstream& summary) {
    output_set outputs;
    atomic_file out(f.partial, inputs);
    write_csv(out, scene, r, outputs);
    summary << "  wrote   " << f.partial << " (" << r.rows.size() << " samples, partial)\n";
    std::string events;
    std::optional<atomic_file> ev;
    if (!f.partial_events.empty()) {
        write_events(ev.emplace(f.partial_events, inputs), scene, r, outputs);
        summary << "  wrote   " << f.partial_events << " (" << r.event_rows.size()
                << " events, partial)\n";
        events =
            " and its " + std::to_string(r.event_rows.size()) + " events in " + f.partial_events;
    }
    commit_outputs(outputs, summary.str(), q, f.csv);
    std::cerr << "rotgen: error: " << to_string(scene.integrator_where)
              << ": the run stopped at t = " << format_double(r.t_reached) << " of "
              << format_double(scene.t_end) << ": " << r.message << "; the " << r.rows.size()
              << " samples computed so far are in " << f.partial << events << "\n";
    return 3;
}

figure_request figures_of(const simulate_request& q) {
    return {q.plot_axis, q.plot_polhode};
}

// What the run records: the scene's columns, and what the page and the figures need.
scene_spec scene_to_run(const simulate_request& q, const scene_spec& scene) {
    const figure_request f = figures_of(q);
    check_figures(f, scene);
    if (q.view.empty() && f.axis.empty() && f.polhode.empty()) return scene;
    return with_records(q.view.empty() ? scene : scene_for_view(scene, "--view"),
                        figure_records(f, scene));
}

// The plot, the page and the figures, from the run (`run`, with what they need recorded) or
// the scene's columns of it (`r`), handed to `outputs`; `csv`: the file the samples are in.
void write_pictures(const simulate_request& q, const scene_spec& scene, const scene_spec& viewed,
                    const run_result& run, const run_result& r, const std::string& csv,
                    const std::vector<std::string>& inputs, stage_timings& timings,
                    std::ostream& summary, output_set& outputs) {
    if (!q.plot.empty()) {
        timings.time("plot", q.plot, [&] { draw_plot(q, csv, scene, r, outputs); });
        summary << "  wrote   " << q.plot << "\n";
    }
    const std::string line = provenance(scene);
    if (!q.plot_axis.empty()) {
        timings.time("plot", q.plot_axis,
                     [&] { draw_axis_figure(q.plot_axis, scene, run, inputs, line, outputs); });
        summary << "  wrote   " << q.plot_axis
                << " (its data: " << figure_data_path(q.plot_axis, "axis") << ")\n";
    }
    if (!q.plot_polhode.empty()) {
        timings.time("plot", q.plot_polhode,
                     [&] { draw_polhode(q.plot_polhode, scene, run, inputs, line, outputs); });
        summary << "  wrote   " << q.plot_polhode
                << " (its data: " << figure_data_path(q.plot_polhode, "polhode") << ")\n";
    }
    if (!q.view.empty()) {
        view_data page = view_of_run(viewed, run);
        page.title = scene.model.name + " (" + q.scene + ")";
        page.source = q.scene;
        timings.time("write", q.view, [&] { write_view(q.view, page, inputs, &outputs); });
        summary << "  wrote   " << q.view << " (the run in 3D: open it in a browser)\n";
    }
}

// The scene, continued from the last row of q.from when given.
scene_spec scene_of(const simulate_request& q) {
    scene_spec scene = load_scene(q.scene, "simulate");
    if (!q.from.empty()) continue_from(scene, q.from);
    return scene;
}

} // namespace

int simulate(const simulate_request& q) {
    const scene_spec scene = scene_of(q);
    std::vector<std::string> inputs{q.scene, scene.model.file};
    if (!q.from.empty()) inputs.push_back(q.from);
    const run_files files = files_of(q, scene);
    const std::string &csv = files.csv, &events = files.events;
    // Output paths are checked before any work (no partial output, early clear error).
    check_files(q, scene, files);
    if (!q.plot.empty()) plot_terminal(q.plot, 1);
    atomic_file csv_out(csv, inputs);
    if (!q.plot.empty()) atomic_file probe(q.plot, inputs);
    std::optional<atomic_file> events_out;
    if (!events.empty()) events_out.emplace(events, inputs);
    for (const auto& file : {q.view, q.plot_axis, q.plot_polhode})
        if (!file.empty()) atomic_file probe(file, inputs);
    const scene_spec viewed = scene_to_run(q, scene);

    stage_timings timings;
    std::ostringstream summary; // written with the outputs (commit_outputs)
    progress_line progress(scene.t_start, scene.t_end, !q.quiet);
    const run_result run = run_scene(viewed, timings, [&](double t) { progress.update(t); });
    const bool extra = !q.view.empty() || !q.plot_axis.empty() || !q.plot_polhode.empty();
    const run_result r = extra ? only_scene_records(run, scene) : run;
    progress.finish();
    print_summary(summary, q, scene, r, timings);
    if (!r.ok) {
        const int status = report_partial(inputs, files, q, scene, r, summary);
        if (q.timings) timings.print(std::cerr);
        return status;
    }
    output_set outputs; // every output appears together, or none does
    timings.time("write", csv, [&] { write_csv(csv_out, scene, r, outputs); });
    summary << "  wrote   " << (csv == "-" ? "standard output" : csv) << " (" << r.rows.size()
            << " samples" << (q.csv.empty() ? ", the default name: -o chooses another" : "")
            << ")\n";
    if (events_out) {
        timings.time("write", events, [&] { write_events(*events_out, scene, r, outputs); });
        summary << "  wrote   " << (events == "-" ? "standard output" : events) << " ("
                << r.event_rows.size() << " events"
                << (scene.events.empty() ? "; the scene has no events:" : "") << ")\n";
    }
    write_pictures(q, scene, viewed, run, r, csv_out.temporary(), inputs, timings, summary,
                   outputs);
    commit_outputs(outputs, summary.str(), q, csv);
    if (q.timings) timings.print(std::cerr);
    return 0;
}

} // namespace rotgen
