#include "simulate/figures.hpp"

#include "simulate/plot.hpp"
#include "support/atomic_file.hpp"
#include "support/error.hpp"
#include "support/format.hpp"
#include "support/gnuplot.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace rotgen {

namespace {

const double pi = 3.14159265358979323846;

// The column `name` of the run (after t), or an internal error: figure_records asked for it.
std::size_t column_of(const run_result& run, const std::string& name) {
    const auto it = std::find(run.columns.begin(), run.columns.end(), name);
    if (it == run.columns.end()) throw std::logic_error("figures: the run did not record " + name);
    return static_cast<std::size_t>(it - run.columns.begin()) + 1;
}

// Writes the provenance line, `header` and `rows` to the figure's data file, handed to `outputs`;
// returns the file gnuplot reads meanwhile (its temporary).
std::string write_data(const std::string& figure, const std::string& kind,
                       const std::string& header, const std::vector<std::vector<double>>& rows,
                       const std::vector<std::string>& inputs, const std::string& provenance,
                       output_set& outputs) {
    atomic_file out(figure_data_path(figure, kind), inputs);
    const std::string written = out.temporary().empty() ? out.path() : out.temporary();
    out.stream() << provenance << "\n" << header << "\n";
    for (const auto& row : rows) {
        for (std::size_t i = 0; i < row.size(); ++i)
            out.stream() << (i ? "," : "") << format_number(row[i]);
        out.stream() << "\n";
    }
    out.commit(outputs);
    return written;
}

// t, the tip of the figure axis (x, y, z), its polar angle from the vertical and its azimuth,
// unwrapped so that the path is continuous (the azimuth of (sin θ sin φ, −sin θ cos φ) is φ).
std::vector<std::vector<double>> axis_rows(const scene_spec& scene, const run_result& run) {
    std::vector<std::vector<double>> rows;
    double azimuth = 0;
    for (const auto& r : run.rows) {
        double x, y, z;
        if (scene.model.rotor) {
            const double phi = r[column_of(run, "phi")], theta = r[column_of(run, "theta")];
            x = std::sin(theta) * std::sin(phi), y = -std::sin(theta) * std::cos(phi);
            z = std::cos(theta);
        } else {
            x = r[column_of(run, "body_z_x")], y = r[column_of(run, "body_z_y")];
            z = r[column_of(run, "body_z_z")];
        }
        const double a = std::atan2(x, -y);
        // the unwrapped azimuth moves by less than pi between samples
        azimuth = rows.empty() ? a : azimuth + std::remainder(a - azimuth, 2 * pi);
        rows.push_back({r[0], x, y, z, std::acos(std::clamp(z, -1.0, 1.0)), azimuth});
    }
    return rows;
}

std::string axis_script(const std::string& output, const std::string& file, const std::string& data,
                        const std::string& title) {
    std::ostringstream s;
    const std::string d = "'" + gnuplot_escape(data) + "'";
    s << "set terminal " << plot_terminal(file, 2) << "\nset output '" << gnuplot_escape(output)
      << "'\nset datafile separator ','\nset grid\nset key off\n"
      << "set multiplot layout 1,2 title '" << gnuplot_escape(title)
      << "'\n"
      // left: the tip seen from above, inside the unit circle (the horizon)
      << "stats " << d << " using 5 every ::1 nooutput\n" // the extreme polar angles
      << "set size ratio -1\nset title 'the axis tip seen from above (x, y)'\n"
      << "set xlabel 'x'\nset ylabel 'y'\nset parametric\nset trange [0:2*pi]\n"
      << "plot cos(t), sin(t) lc rgb 'gray', sin(STATS_min)*cos(t), sin(STATS_min)*sin(t) dt 2 "
      << "lc rgb 'gray', sin(STATS_max)*cos(t), sin(STATS_max)*sin(t) dt 2 lc rgb 'gray', " << d
      << " using 2:3 every ::1 with lines lw 1.5\n"
      << "unset parametric\nset size noratio\n"
      // right: the polar angle against the azimuth, the upright axis at the top
      << "set title 'the polar angle of the axis against its azimuth'\n"
      << "set xlabel 'azimuth (rad)'\nset ylabel 'polar angle from the vertical (rad)'\n"
      << "set yrange [*:*] reverse\n"
      << "plot " << d << " using 6:5 every ::1 with lines lw 1.5\n"
      << "unset multiplot\n";
    return s.str();
}

// t, ω and L in the body frame, then 2T = ω·L and L² = L·L (both constant for a free body).
std::vector<std::vector<double>> polhode_rows(const run_result& run) {
    std::vector<std::vector<double>> rows;
    const std::size_t w = column_of(run, "omega1"), l = column_of(run, "L1");
    for (const auto& r : run.rows) {
        double two_t = 0, l2 = 0;
        for (std::size_t i = 0; i < 3; ++i)
            two_t += r[w + i] * r[l + i], l2 += r[l + i] * r[l + i];
        rows.push_back({r[0], r[w], r[w + 1], r[w + 2], r[l], r[l + 1], r[l + 2], two_t, l2});
    }
    return rows;
}

std::string polhode_script(const std::string& output, const std::string& file,
                           const std::string& data, const std::string& title, double radius) {
    std::ostringstream s;
    const std::string d = "'" + gnuplot_escape(data) + "'", r = format_number(radius);
    s << "set terminal " << plot_terminal(file, 2) << "\nset output '" << gnuplot_escape(output)
      << "'\nset datafile separator ','\nset key off\nset view equal xyz\n"
      << "set view 60, 30\nset xyplane 0\nset parametric\nset isosamples 25, 13\n"
      << "set urange [0:2*pi]\nset vrange [-pi/2:pi/2]\nset hidden3d front\n"
      << "set title '" << gnuplot_escape(title)
      << ": the body angular momentum L on its sphere |L| = const (the polhode)'\n"
      << "set xlabel 'L1'\nset ylabel 'L2'\nset zlabel 'L3'\n"
      << "splot " << r << "*cos(u)*cos(v), " << r << "*sin(u)*cos(v), " << r
      << "*sin(v) with lines lc rgb '#c8c8c8', " << d
      << " using 5:6:7 every ::1 with lines lw 2.5 lc rgb '#b00000'\n";
    return s.str();
}

} // namespace

std::string figure_data_path(const std::string& figure, const std::string& kind) {
    const std::size_t slash = figure.find_last_of('/');
    const std::size_t dot = figure.rfind('.');
    // "run.png" and "out/run.png" have one; "out/run", ".hidden" and "out.d/run" have none
    const std::size_t name = slash == std::string::npos ? 0 : slash + 1;
    const bool has_extension = dot != std::string::npos && dot > name;
    return (has_extension ? figure.substr(0, dot) : figure) + "." + kind + ".csv";
}

void check_figures(const figure_request& q, const scene_spec& scene) {
    for (const auto& [file, option] :
         {std::pair{q.axis, "--plot-axis"}, std::pair{q.polhode, "--plot-polhode"}})
        if (!file.empty() && scene.form == form_kind::reduced)
            throw user_error({option}, "the figure needs the attitude and the angular velocity, "
                                       "which the reduced form does not keep: use another form");
    if (!q.axis.empty()) plot_terminal(q.axis, 2);
    if (!q.polhode.empty()) {
        plot_terminal(q.polhode, 2);
        if (scene.model.rotor)
            throw user_error({"--plot-polhode"},
                             "a linear rotor has no polhode (its angular velocity is across its "
                             "line, L / I); use --plot-axis for the path of its line");
    }
}

std::vector<std::string> figure_records(const figure_request& q, const scene_spec& scene) {
    std::vector<std::string> wanted;
    if (!q.axis.empty()) {
        if (scene.model.rotor)
            wanted.insert(wanted.end(), {"phi", "theta"});
        else
            wanted.push_back("body_z");
    }
    if (!q.polhode.empty())
        wanted.insert(wanted.end(), {"omega1", "omega2", "omega3", "L1", "L2", "L3"});
    return wanted;
}

void draw_axis_figure(const std::string& file, const scene_spec& scene, const run_result& run,
                      const std::vector<std::string>& inputs, const std::string& provenance,
                      output_set& outputs) {
    const std::string data = write_data(file, "axis", "t,x,y,z,polar,azimuth",
                                        axis_rows(scene, run), inputs, provenance, outputs);
    draw_with_gnuplot(
        file,
        [&](const std::string& output) {
            return axis_script(output, file, data,
                               scene.model.name + ": the figure axis on the unit sphere");
        },
        &outputs);
}

void draw_polhode(const std::string& file, const scene_spec& scene, const run_result& run,
                  const std::vector<std::string>& inputs, const std::string& provenance,
                  output_set& outputs) {
    const auto rows = polhode_rows(run);
    const std::string data =
        write_data(file, "polhode", "t,omega1,omega2,omega3,L1,L2,L3,two_T,L_squared", rows, inputs,
                   provenance, outputs);
    const double radius = rows.empty() ? 1.0 : std::sqrt(rows.front()[8]);
    draw_with_gnuplot(
        file,
        [&](const std::string& output) {
            return polhode_script(output, file, data, scene.model.name, radius);
        },
        &outputs);
}

} // namespace rotgen
