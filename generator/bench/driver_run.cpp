// rotgen bench: running the driver, and reading what it wrote.
#include "bench/driver.hpp"

#include "bench/sampled_error.hpp"
#include "support/process.hpp"

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

namespace rotgen::bench {

namespace {

namespace fs = std::filesystem;

std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string one;
    in >> one;
    return one.empty() ? std::string("?") : one;
}

double parse_number(const std::string& s) {
    if (s == "nan" || s == "-nan") return NAN;
    return std::strtod(s.c_str(), nullptr);
}

// The fields after "row": variant peer method form scalar tol step status error orientation
// rhs jac steps median min max energy_drift momentum_drift n y_1 .. y_n.
result_row parse_row(std::istream& is) {
    result_row r;
    std::string tol, step, err, orient, med, mn, mx, ed, md;
    std::size_t n = 0;
    is >> r.variant >> r.peer >> r.method >> r.form >> r.scalar >> tol >> step >> r.status >> err >>
        orient >> r.rhs >> r.jac >> r.steps >> med >> mn >> mx >> ed >> md >> n;
    r.tol = parse_number(tol);
    r.step = parse_number(step);
    r.error = parse_number(err);
    r.orientation = parse_number(orient);
    r.median = parse_number(med);
    r.min = parse_number(mn);
    r.max = parse_number(mx);
    r.energy_drift = parse_number(ed);
    r.momentum_drift = parse_number(md);
    for (std::size_t i = 0; i < n; ++i) {
        std::string v;
        is >> v;
        r.y.push_back(v);
    }
    return r;
}

// The fields after "drift": label steps rhs t relative_energy_error.
drift_point parse_drift(std::istream& is) {
    drift_point p;
    std::string t, e;
    is >> p.label >> p.steps >> p.rhs >> t >> e;
    p.t = parse_number(t);
    p.e = parse_number(e);
    return p;
}

// One line of raw.txt into `out`; lines of other kinds are ignored.
void read_line(const std::string& line, driver_output& out) {
    std::istringstream is(line);
    std::string what;
    is >> what;
    if (what == "compared") {
        std::getline(is, out.compared);
        if (!out.compared.empty() && out.compared[0] == ' ') out.compared.erase(0, 1);
    } else if (what == "reference") {
        std::string e, o;
        is >> out.reference_source >> e >> o;
        out.reference_error = parse_number(e);
        out.reference_orientation = parse_number(o);
    } else if (what == "reference_run") {
        std::string rest;
        std::getline(is, rest);
        out.reference_runs.push_back(rest);
    } else if (what == "row") {
        out.rows.push_back(parse_row(is));
    } else if (what == "drift") {
        out.drift_points.push_back(parse_drift(is));
    } else if (what == "drift_failed") {
        std::string label, why;
        is >> label >> why;
        out.drift_failed[label] = why;
    }
}

} // namespace

driver_run run_driver(const fs::path& exe, const fs::path& dir, std::size_t configurations) {
    driver_run r;
    r.load_before = load_average();
    const auto t_run = std::chrono::steady_clock::now();
    r.raw = dir / "raw.txt";
    std::cout << "rotgen bench: running the sweep (" << configurations << " configurations) ..."
              << std::flush;
    int status = 0;
    const std::string log =
        run_capture(shell_quote(exe.string()) + " " + shell_quote((dir / "plan.txt").string()) +
                        " " + shell_quote(r.raw.string()),
                    &status);
    if (status != 0)
        throw std::runtime_error("the work-precision driver failed (status " +
                                 std::to_string(status) + "): " + log.substr(0, 2000));
    std::cout << " done\n";
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_run).count();
    r.load_after = load_average();
    return r;
}

driver_output read_output(const fs::path& raw) {
    driver_output out;
    std::ifstream in(raw);
    std::string line;
    while (std::getline(in, line))
        read_line(line, out);
    if (out.rows.empty())
        throw std::runtime_error("the work-precision driver wrote no results (" + raw.string() +
                                 ")");
    for (result_row& r : out.rows) // issue 50: errors the reference cannot tell apart from its own
        r.at_floor = r.error <= floor_factor * out.reference_error;
    return out;
}

} // namespace rotgen::bench
