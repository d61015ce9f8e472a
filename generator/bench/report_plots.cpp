// rotgen bench: the plots — work_precision_time.png, work_precision_evals.png and
// invariant_drift.png, drawn by gnuplot.
#include "bench/bench_internal.hpp"
#include "bench/files.hpp"
#include "bench/numbers.hpp"
#include "support/error.hpp"
#include "support/gnuplot.hpp"
#include "support/process.hpp"

#include <unistd.h>

#include <algorithm>
#include <map>
#include <sstream>

namespace rotgen::bench {

namespace {

namespace fs = std::filesystem;

// One curve of a plot: the points of one configuration (method, peer, form, scalar).
struct curve {
    std::string key, title, panel;
    int color = 0, dash = 1, point = 1;
    std::vector<const result_row*> points;
};

const char* const palette =
    "set linetype 1 lc rgb '#1f77b4'\nset linetype 2 lc rgb '#ff7f0e'\nset linetype 3 lc rgb "
    "'#2ca02c'\nset linetype 4 lc rgb '#d62728'\nset linetype 5 lc rgb '#9467bd'\nset linetype "
    "6 lc rgb '#8c564b'\nset linetype 7 lc rgb '#e377c2'\nset linetype 8 lc rgb '#7f7f7f'\nset "
    "linetype 9 lc rgb '#bcbd22'\nset linetype 10 lc rgb '#17becf'\nset linetype 11 lc rgb "
    "'#000000'\nset linetype 13 lc rgb '#b8e186'\nset linetype 14 lc rgb '#01665e'\nset "
    "linetype 15 lc rgb '#003300'\nset linetype 16 lc rgb '#a00000'\n";

// `terminal`, then the output (a temporary PNG renamed to `png` once gnuplot succeeded), then
// `body`, written to `script_path` and run by gnuplot; throws user_error if it fails.
void run_gnuplot(const fs::path& script_path, const std::string& terminal, const std::string& body,
                 const fs::path& png) {
    const std::string tmp_png = png.string() + ".tmp" + std::to_string(::getpid()) + ".png";
    write_file(script_path, terminal + "set output '" + gnuplot_escape(tmp_png) + "'\n" + body);
    run_gnuplot_script(script_path.string(), tmp_png, png.string());
}

int color_of(const std::string& peer, const std::string& method) {
    static const std::map<std::string, int> colors{
        {"rotgen rk4", 1},           {"rotgen dopri5", 2},
        {"rotgen dop853", 3},        {"rotgen implicit_midpoint", 4},
        {"rotgen rodas4", 5},        {"odeint dopri5", 6},
        {"odeint rkf78", 7},         {"odeint rk4", 8},
        {"cvode adams", 9},          {"cvode bdf", 10},
        {"rotgen dop853 fixed", 11}, {"odeint rkf78 fixed", 12},
        {"rotgen split2", 13},       {"rotgen split4", 14},
        {"rotgen split6", 15},       {"rotgen taylor", 16}};
    const auto it = colors.find(peer + " " + method);
    return it == colors.end() ? 17 : it->second;
}

// The panels a row is drawn in: (a) the integrators and peers on the main form in double (and
// the split methods on theirs), (b) the forms and code generation, (c) the scalar types.
std::vector<std::string> panels_of(const result_row& r) {
    std::vector<std::string> panels;
    const std::string m = method_key(r);
    if ((r.variant == 0 || m.rfind("split", 0) == 0) && r.scalar == "double") panels.push_back("a");
    if (r.peer == "rotgen" && r.scalar == "double" &&
        (m == "dop853" || m == "rk4" || m == "implicit_midpoint"))
        panels.push_back("b");
    if (r.peer == "rotgen" && r.variant == 0 && (m == "dop853" || m == "dopri5" || m == "rk4"))
        panels.push_back("c");
    return panels;
}

// Curves: one per (panel, peer, method, form, scalar), in the order of their first point.
std::vector<curve> collect_curves(const std::vector<result_row>& rows) {
    std::vector<curve> curves;
    for (const auto& r : rows) {
        if (!r.ok() || !(r.error > 0) || !std::isfinite(r.median)) continue;
        const std::string m = method_key(r);
        for (const auto& panel : panels_of(r)) {
            const std::string key = panel + "|" + r.peer + "|" + m + "|" + r.form + "|" + r.scalar;
            auto it = std::find_if(curves.begin(), curves.end(),
                                   [&](const curve& c) { return c.key == key; });
            if (it == curves.end()) {
                curve c;
                c.key = key;
                c.panel = panel;
                c.title = method_title(r) + (panel == "b" ? " " + r.form : "") +
                          (panel == "c" ? " " + r.scalar : "");
                c.color = panel == "a" ? color_of(r.peer, m) : 0;
                c.dash = r.peer == "rotgen" ? 1 : r.peer == "odeint" ? 2 : 3;
                c.point = panel == "a" ? color_of(r.peer, m) : 1;
                curves.push_back(c);
                it = curves.end() - 1;
            }
            it->points.push_back(&r);
        }
    }
    return curves;
}

// Colours within panels b and c: by form / scalar; dash by method. Points sorted by tolerance
// or step.
void style_curves(std::vector<curve>& curves) {
    std::map<std::string, int> form_colors, scalar_colors;
    for (auto& c : curves) {
        const result_row& r = *c.points.front();
        if (c.panel == "b") {
            if (!form_colors.count(r.form)) form_colors[r.form] = int(form_colors.size()) + 1;
            c.color = form_colors[r.form];
            c.dash = r.method == "dop853" ? 1 : r.method == "rk4" ? 2 : 4;
            c.point = r.method == "dop853" ? 7 : r.method == "rk4" ? 5 : 9;
        } else if (c.panel == "c") {
            if (!scalar_colors.count(r.scalar))
                scalar_colors[r.scalar] = int(scalar_colors.size()) + 1;
            c.color = scalar_colors[r.scalar];
            c.dash = r.method == "dop853" ? 1 : r.method == "dopri5" ? 2 : 4;
            c.point = r.method == "dop853" ? 7 : r.method == "dopri5" ? 5 : 9;
        }
        std::sort(c.points.begin(), c.points.end(), [](const result_row* a, const result_row* b) {
            return a->tol > 0 ? a->tol > b->tol : a->step > b->step;
        });
    }
}

// plot_data.dat: one gnuplot data block per curve (median time, RHS evaluations, error).
void write_plot_data(const fs::path& path, const std::vector<curve>& curves) {
    std::ostringstream data;
    for (const auto& c : curves) {
        data << "# " << c.title << "\n";
        for (const auto* r : c.points)
            data << plain(r->median) << " " << r->rhs << " " << plain(r->error) << "\n";
        data << "\n\n";
    }
    write_file(path, data.str());
}

// One panel's plot command: its curves from plot_data.dat, x from `column`.
void plot_panel(std::ostream& gp, const std::vector<curve>& curves, const std::string& panel,
                const fs::path& data, int column) {
    bool first = true;
    for (std::size_t i = 0; i < curves.size(); ++i) {
        if (curves[i].panel != panel) continue;
        gp << (first ? "" : ", \\\n     ") << "'" << gnuplot_escape(data.string()) << "' index "
           << i << " using " << column << ":3 with linespoints lt " << curves[i].color << " dt "
           << curves[i].dash << " pt " << curves[i].point << " ps 0.8 lw 1.5 title '"
           << gnuplot_escape(curves[i].title) << "'";
        first = false;
    }
    if (first) gp << "1/0 notitle";
    gp << "\n";
}

// The three panels, error against time (column 1) or RHS evaluations (column 2).
void work_precision_plot(const bench_context& ctx, const std::vector<curve>& curves,
                         const std::string& file, int column, const std::string& xlabel) {
    const std::string& main_label = ctx.variants.variants[0].label;
    const auto sv = split_variant(ctx.variants.variants);
    const bool split_apart = sv && *sv != 0 && !ctx.extra.split_refusal;
    std::ostringstream gp;
    gp << palette << "set logscale xy\nset grid\nset format y '1e%T'\nset format x '1e%T'\n"
       << "set key outside right top Left reverse samplen 3\n"
       << "set xlabel '" << xlabel << "'\nset ylabel 'largest error at the samples, t0 .. "
       << plain(ctx.plan.t1) << "'\n"
       << "set multiplot layout 3,1 title '" << gnuplot_escape(ctx.scene_name)
       << ": work-precision (" << gnuplot_escape(ctx.output.compared)
       << "); solid rotgen, dashed Odeint, dotted CVODE'\n";
    const std::vector<std::pair<std::string, std::string>> panel_titles{
        {"a", "integrators and peers on " + main_label + " (double" +
                  (split_apart ? "; split methods on body:quaternion" : "") + ")"},
        {"b", "formulations and code generation (rotgen, double): solid dop853, dashed rk4, "
              "dotted midpoint"},
        {"c", "scalar types on " + main_label + ": solid dop853, dashed dopri5, dotted rk4"}};
    for (const auto& [panel, title] : panel_titles) {
        gp << "set title '" << gnuplot_escape(title) << "'\nplot ";
        plot_panel(gp, curves, panel, ctx.dir / "plot_data.dat", column);
    }
    gp << "unset multiplot\n";
    run_gnuplot(ctx.dir / (file + ".gp"),
                "set terminal pngcairo size 1600,1500 noenhanced font ',10'\n", gp.str(),
                ctx.dir / file);
}

// The long runs' relative energy error against time: drift_data.dat and invariant_drift.png.
void drift_plot(const bench_context& ctx) {
    const auto& labels = ctx.plan.drift_labels;
    std::ostringstream data;
    for (const auto& label : labels) {
        data << "# " << label << "\n";
        for (const auto& p : ctx.output.drift_points)
            if (p.label == label && p.t > ctx.plan.t0)
                data << plain(p.t - ctx.plan.t0) << " " << plain(std::max(p.e, 1e-19)) << "\n";
        data << "\n\n";
    }
    write_file(ctx.dir / "drift_data.dat", data.str());
    std::ostringstream gp;
    gp << palette << "set logscale xy\nset grid\nset format y '1e%T'\n"
       << "set key outside right top Left reverse\n"
       << "set xlabel 't - t0'\nset ylabel '|E(t) - E(0)| / |E(0)|'\n"
       << "set title '" << gnuplot_escape(ctx.scene_name) << ": energy error over "
       << ctx.opt.long_steps << " steps of h = " << short_number(0.3 / ctx.plan.nu)
       << " (adaptive runs over the same time)'\n"
       << "plot ";
    for (std::size_t i = 0; i < labels.size(); ++i)
        gp << (i ? ", \\\n     " : "") << "'"
           << gnuplot_escape((ctx.dir / "drift_data.dat").string()) << "' index " << i
           << " using 1:2 with lines lw 1.5 lt " << (i + 1) << " title '"
           << gnuplot_escape(labels[i]) << "'";
    gp << "\n";
    run_gnuplot(ctx.dir / "invariant_drift.gp",
                "set terminal pngcairo size 1100,650 noenhanced font ',10'\n", gp.str(),
                ctx.dir / "invariant_drift.png");
}

} // namespace

void draw_plots(const bench_context& ctx) {
    std::vector<curve> curves = collect_curves(ctx.output.rows);
    style_curves(curves);
    write_plot_data(ctx.dir / "plot_data.dat", curves);
    work_precision_plot(ctx, curves, "work_precision_time.png", 1,
                        "time per integration (s), median of " + std::to_string(ctx.plan.repeats));
    work_precision_plot(ctx, curves, "work_precision_evals.png", 2, "RHS evaluations");
    if (!ctx.plan.drift_labels.empty()) drift_plot(ctx);
}

} // namespace rotgen::bench
