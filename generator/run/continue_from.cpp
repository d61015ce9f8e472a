#include "run/continue_from.hpp"

#include "support/error.hpp"
#include "support/format.hpp"

#include "expr/symbols.hpp"
#include "run/angle_chart.hpp"
#include "run/provenance.hpp"

#include <Eigen/Geometry>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>

namespace rotgen {

namespace {

// The cells of a CSV line and the column (1-based) where each starts.
std::vector<std::string> split(const std::string& line, std::vector<int>& starts) {
    std::vector<std::string> cells(1);
    starts.assign(1, 1);
    for (std::size_t i = 0; i < line.size(); ++i) {
        if (line[i] != ',') {
            cells.back() += line[i];
            continue;
        }
        cells.emplace_back();
        starts.push_back(static_cast<int>(i) + 2);
    }
    return cells;
}

// Refuses a run that another model or form made, or one without a provenance line (line 1).
void check_provenance(const std::string& csv, const std::string& first_line,
                      const scene_spec& scene) {
    const std::optional<csv_provenance> run = parse_provenance(first_line);
    if (!run)
        throw user_error({csv, 1, 1}, "line 1 is not rotgen's provenance line ('# rotgen VERSION "
                                      "model NAME sha256 HASH form FORM'): --from continues only "
                                      "a run that rotgen simulate wrote");
    const csv_provenance here = provenance_of(scene.model, scene.form);
    if (run->model == here.model && run->sha256 == here.sha256 && run->form == here.form) return;
    const auto which = [](const csv_provenance& p) {
        return "'" + p.model + "' (sha256 " + p.sha256.substr(0, 12) + ", " + p.form + " form)";
    };
    throw user_error({csv, 1, 1}, "the run is of model " + which(*run) +
                                      ", not of this scene's "
                                      "model " +
                                      which(here) +
                                      ": --from continues a run of the same "
                                      "model and form");
}

// The header and the last non-empty row of `csv`, its numbers read back exactly (strtod); line 1
// is the provenance line.
start_row read_last_row(const std::string& csv, const scene_spec& scene) {
    std::ifstream in(csv, std::ios::binary);
    if (!in)
        throw user_error({csv, 0, 0}, std::string("cannot read the run to continue from: ") +
                                          std::strerror(errno));
    std::string line, first, header, last;
    int n = 0;
    start_row row;
    row.file = csv;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (++n == 1)
            first = line;
        else if (n == 2)
            header = line;
        else if (!line.empty())
            last = line, row.line = n;
    }
    check_provenance(csv, first, scene);
    std::vector<int> starts;
    row.names = split(header, starts);
    if (row.names[0] != "t")
        throw user_error({csv, 2, 1}, "not a CSV written by rotgen simulate (its header does not "
                                      "start with t): nothing to continue from");
    if (row.line == 0) throw user_error({csv, 2, 1}, "the run has no rows to continue from");
    const std::vector<std::string> cells = split(last, starts);
    if (cells.size() != row.names.size())
        throw user_error({csv, row.line, 1}, "the last row has " + std::to_string(cells.size()) +
                                                 " values for the header's " +
                                                 std::to_string(row.names.size()) + " columns");
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const char* text = cells[i].c_str();
        char* end = nullptr;
        const double v = std::strtod(text, &end);
        if (cells[i].empty() || end != text + cells[i].size() || !std::isfinite(v))
            throw user_error({csv, row.line, starts[i]},
                             row.names[i] + " = '" + cells[i] +
                                 "' is not a finite number: this row cannot start a run");
        row.values.push_back(v);
    }
    return row;
}

// The recorded columns that make a state of the scene's form (reduced: those every reduced form
// needs; check_start_row checks the angles it keeps).
std::vector<std::string> required_names(form_kind form, const angle_convention& c) {
    const auto& q = c.names;
    switch (form) {
    case form_kind::lagrangian:
        return {q[0], q[1], q[2], q[0] + "_dot", q[1] + "_dot", q[2] + "_dot"};
    case form_kind::hamiltonian:
        return {q[0], q[1], q[2], "p_" + q[0], "p_" + q[1], "p_" + q[2]};
    case form_kind::reduced:
        return {q[1], "p_" + q[0], "p_" + q[1], "p_" + q[2]};
    case form_kind::body:
        return {"q0", "q1", "q2", "q3", "omega1", "omega2", "omega3"};
    default:
        return {"phi", "theta", "phi_dot", "theta_dot"}; // a linear rotor
    }
}

// Refuses a row without all of `names`, naming the missing ones.
void require(const start_row& row, const std::vector<std::string>& names, form_kind form) {
    std::string missing;
    for (const auto& name : names)
        if (std::isnan(row_value(row, name))) missing += (missing.empty() ? "" : ", ") + name;
    if (missing.empty()) return;
    std::string all;
    for (const auto& name : names)
        all += (all.empty() ? "" : ", ") + name;
    throw user_error({row.file, 2, 1}, "the last row (line " + std::to_string(row.line) +
                                           ") is not a complete state of the " + to_string(form) +
                                           " form: it lacks " + missing + " (record " + all +
                                           " in the run to continue)");
}

written_value plain(double v) {
    written_value w;
    w.value = v;
    return w;
}

// The scene's initial angles and rates from the row (plain numbers: they are exact as written).
void set_initial(scene_spec& scene, const start_row& row) {
    const auto v = [&](const std::string& name) {
        const double x = row_value(row, name);
        return std::isnan(x) ? 0.0 : x; // an angle the reduced form ignores
    };
    const angle_convention& c = scene.model.angles;
    const auto& q = c.names;
    std::array<std::string, 3> rates{q[0] + "_dot", q[1] + "_dot", q[2] + "_dot"};
    scene.initial = initial_kind::rates;
    if (scene.form == form_kind::hamiltonian || scene.form == form_kind::reduced)
        rates = {"p_" + q[0], "p_" + q[1], "p_" + q[2]}, scene.initial = initial_kind::momenta;
    if (scene.form == form_kind::body)
        rates = {"omega1", "omega2", "omega3"}, scene.initial = initial_kind::omega;
    std::array<double, 3> angles{0, 0, 0};
    if (scene.form == form_kind::body)
        angles = angles_of_quaternion(
            sequence_of(c), Eigen::Quaterniond(v("q0"), v("q1"), v("q2"), v("q3")).normalized());
    else
        angles = {v(q[0]), v(q[1]), v(q[2])};
    for (std::size_t i = 0; i < 3; ++i) {
        scene.angles[i] = angles[i], scene.angles_written[i] = plain(angles[i]);
        scene.initial_rates[i] = v(rates[i]), scene.rates_written[i] = plain(v(rates[i]));
    }
    const bool proper = c.proper();
    const double lo = proper ? 0 : -1.570796326794896619,
                 hi = proper ? 3.141592653589793238 : 1.570796326794896619;
    if (!(angles[1] >= lo && angles[1] <= hi))
        throw user_error({row.file, row.line, 1},
                         q[1] + " = " + format_number(angles[1]) + " is outside " +
                             (proper ? "[0, pi]" : "[-pi/2, pi/2]") + " (" + c.description() + ")");
}

} // namespace

double row_value(const start_row& row, const std::string& name) {
    for (std::size_t i = 0; i < row.names.size(); ++i)
        if (row.names[i] == name) return row.values[i];
    return std::numeric_limits<double>::quiet_NaN();
}

void continue_from(scene_spec& scene, const std::string& csv) {
    start_row row = read_last_row(csv, scene);
    require(row, required_names(scene.form, scene.model.angles), scene.form);
    scene.t_start = row.values[0];
    if (scene.t_end == scene.t_start)
        throw user_error(scene.time_where,
                         "the run in " + csv + " ends at t = " + format_double(scene.t_start) +
                             ", this scene's end time: nothing to continue (change time end)");
    const integrator_spec& ig = scene.integrator;
    if (ig.step > 0 && ig.step > std::abs(scene.t_end - scene.t_start))
        throw user_error(scene.integrator_where,
                         "integrator step is longer than the time span from t = " +
                             format_double(scene.t_start) + " (the last row of " + csv + ")");
    set_initial(scene, row);
    continue_wheels(scene, row);
    scene.initial_where = {csv, row.line, 1};
    scene.from = std::move(row);
}

void check_start_row(const start_row& row, const form_expressions& f) {
    std::vector<std::string> names;
    for (const auto& s : f.state) {
        const std::string& n = s.name;
        names.push_back(n == "qw"   ? "q0"
                        : n == "qx" ? "q1"
                        : n == "qy" ? "q2"
                        : n == "qz" ? "q3"
                                    : n);
    }
    for (const auto& p : f.parameters)
        for (const auto& m : momentum_names(f.angles))
            if (p.name == m) names.push_back(p.name);
    require(row, names, f.form);
}

} // namespace rotgen
