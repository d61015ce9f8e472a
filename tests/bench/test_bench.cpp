// `rotgen bench --quick` end to end (issue 5): the work-precision harness on a tiny sweep of the
// free asymmetric top writes results.csv with the columns of DESIGN.md "Interfaces", results.md
// and the three plots, and its error figures agree with an independent computation of the same
// runs. The error is the one error measure (issue 50): the largest over the scene's samples of
// |omega - omega_ref| / max |omega_ref| (omega is all that every form here determines):
//   - each final state (final_states.csv) against the exact solution, computed here with
//     runtime/exact_free_top.hpp (the harness uses its own attitude-aware reference,
//     bench/workprecision/exact_reference.hpp), mapping Euler-angle states to omega by (5.30)
//     written out here (the body form with the quaternion: its last three states): the end time
//     is a sample, so the row's error is at least the end time's;
//   - the rows of the split methods and the Taylor method (issues 17 and 18) are there, on their
//     forms, with errors consistent with their tolerances;
//   - one configuration re-run here with the runtime on the checked-in generated header
//     (generated/free_asymmetric_top_body.hpp, run-time parameters), calibrated as simulate
//     calibrates it: same RHS count, same final state, and the same sampled error, which is far
//     above its error at the end time (the bench's tables measured that before issue 50).
// The driver is compiled once and cached in <build>/bench-cache (the first run compiles it).
#include "support.hpp"

#include "bench/sampled_error.hpp"
#include "scene/scene.hpp"

#include "../../generated/free_asymmetric_top_body.hpp"

#include <exact_free_top.hpp>
#include <integrate/integrate.hpp>
#include <steppers/dop853.hpp>
#include <system.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

using namespace rotgen::test;

namespace {

std::vector<std::string> split(const std::string& line, char sep) {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream in(line);
    while (std::getline(in, cell, sep))
        cells.push_back(cell);
    if (!line.empty() && line.back() == sep) cells.push_back("");
    return cells;
}

struct table {
    std::vector<std::string> header;
    std::vector<std::map<std::string, std::string>> rows;
};

// One level of the bench summary's choice: "error <= 1e-08: CONFIG, 12 us (...)" and its scene
// lines.
struct choice {
    std::string level, config;
    std::vector<std::string> lines;
};

std::vector<choice> read_choices(const std::string& out) {
    std::vector<choice> cs;
    for (const std::string& line : text_lines(out)) {
        const std::size_t at = line.find("error <= ");
        if (at != std::string::npos && line.find(": ", at) != std::string::npos &&
            line.find(", ", at) != std::string::npos && line.find("none (") == std::string::npos) {
            const std::size_t colon = line.find(": ", at);
            cs.push_back({line.substr(at + 9, colon - at - 9),
                          line.substr(colon + 2, line.find(", ", colon) - colon - 2),
                          {}});
        } else if (!cs.empty() &&
                   (line.find("    form: ") == 2 || line.find("    integrator: ") == 2))
            cs.back().lines.push_back(line.substr(6));
    }
    return cs;
}

// The scene with a choice's lines for its form and integrator, run and measured with the one
// error measure against its reference.
double run_choice(const std::string& scene, const std::vector<std::string>& lines,
                  const std::string& dir) {
    std::string text;
    for (const std::string& line : text_lines(read_file(scene)))
        if (line.rfind("form:", 0) != 0 && line.rfind("integrator:", 0) != 0)
            text +=
                (line.rfind("model: ", 0) == 0 ? "model: " + std::string(ROTGEN_SOURCE_DIR) +
                                                     "/models/" + line.substr(line.rfind('/') + 1)
                                               : line) +
                "\n";
    for (const std::string& line : lines)
        text += line + "\n";
    const std::string file = dir + "/choice.yaml";
    std::ofstream(file) << text;
    const rotgen::scene_spec chosen = rotgen::load_scene(file);
    const rotgen::bench::reference_run ref =
        rotgen::bench::make_reference(rotgen::load_scene(scene));
    const auto m =
        rotgen::bench::measure_scene(rotgen::bench::scene_for_error(chosen), &ref.result, 1);
    return m.ok ? m.error : NAN;
}

table read_table(const std::string& path) {
    table t;
    std::istringstream in(read_file(path));
    std::string line;
    std::getline(in, line);
    t.header = split(line, ',');
    while (std::getline(in, line)) {
        const auto cells = split(line, ',');
        std::map<std::string, std::string> row;
        for (std::size_t i = 0; i < t.header.size() && i < cells.size(); ++i)
            row[t.header[i]] = cells[i];
        t.rows.push_back(row);
    }
    return t;
}

bool is_png(const std::string& path) {
    const std::string s = read_file(path);
    return s.size() > 1000 && s.compare(0, 4, "\x89PNG") == 0;
}

// The free top: I = (1, 2, 3), omega0 = (1, 0.1, 0.5), t in [0, 100].
const std::array<long double, 3> inertia = {1.0L, 2.0L, 3.0L};
const std::array<long double, 3> omega0 = {1.0L, 0.1L, 0.5L};

// omega = J(q) q_dot, (5.30)
std::array<long double, 3> omega_of(const std::vector<long double>& y) {
    const long double th = y[1], ps = y[2], fd = y[3], td = y[4], pd = y[5];
    return {fd * std::sin(th) * std::sin(ps) + td * std::cos(ps),
            fd * std::sin(th) * std::cos(ps) - td * std::sin(ps), fd * std::cos(th) + pd};
}

// |w - ref|
long double distance(const std::array<long double, 3>& w, const std::array<long double, 3>& ref) {
    return std::hypot(w[0] - ref[0], w[1] - ref[1], w[2] - ref[2]);
}

// The scene's 1001 sample times on [0, 100].
std::vector<double> sample_times() {
    std::vector<double> t(1001);
    for (std::size_t i = 0; i < t.size(); ++i)
        t[i] = i + 1 == t.size() ? 100.0 : 100.0 * double(i) / 1000.0;
    return t;
}

// max |omega_exact| over the samples: the scale of the rate error.
long double omega_scale(const rotgen::free_top_exact<long double>& exact) {
    long double s = 0;
    for (double t : sample_times())
        s = std::max(s, distance(exact((long double)t), {0, 0, 0}));
    return s;
}

} // namespace

TEST_CASE("rotgen bench --quick: columns, plots, and errors that match an independent computation",
          "[bench]") {
    namespace fs = std::filesystem;
    const std::string dir = std::string(ROTGEN_BINARY_DIR) + "/tests_bench_out";
    fs::remove_all(dir);
    ::setenv("ROTGEN_CACHE_DIR", (std::string(ROTGEN_BINARY_DIR) + "/bench-cache").c_str(), 1);
    const std::string scene =
        std::string(ROTGEN_SOURCE_DIR) + "/models/scenes/free_top_workprecision.yaml";
    const run_result r = run_rotgen("bench '" + scene + "' -o '" + dir + "' --quick");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);

    // the files
    for (const char* png :
         {"work_precision_time.png", "work_precision_evals.png", "invariant_drift.png"})
        CHECK(is_png(dir + "/" + png));
    const std::string md = read_file(dir + "/results.md");
    CHECK(md.find("| error <= | rotgen best |") != std::string::npos);
    CHECK(md.find("exact") != std::string::npos);

    // the columns, exactly
    const table csv = read_table(dir + "/results.csv");
    CHECK(csv.header == std::vector<std::string>{"method", "peer", "form", "scalar", "tolerance",
                                                 "step", "error", "orientation_error", "rhs_evals",
                                                 "jac_evals", "time_median_s", "time_min_s",
                                                 "time_max_s", "energy_drift"});
    const table fin = read_table(dir + "/final_states.csv");
    REQUIRE(csv.rows.size() == fin.rows.size());
    REQUIRE(csv.rows.size() >= 15);
    std::map<std::string, int> peers;
    for (const auto& row : csv.rows)
        ++peers[row.at("peer")];
    CHECK(peers["rotgen"] >= 10);
    CHECK(peers["odeint"] >= 1);
    CHECK(peers["cvode"] >= 2);

    // every error recomputed from the written final state against the exact solution
    const rotgen::free_top_exact<long double> exact(inertia, omega0);
    const auto w_end = exact(100.0L);
    const long double scale = omega_scale(exact);
    int checked = 0, lagrangian = 0, quaternion = 0;
    for (std::size_t i = 0; i < csv.rows.size(); ++i) {
        const auto& row = csv.rows[i];
        INFO(row.at("method") << " " << row.at("peer") << " " << row.at("form") << " "
                              << row.at("scalar") << " tol " << row.at("tolerance") << " h "
                              << row.at("step"));
        REQUIRE(fin.rows[i].at("method") == row.at("method"));
        REQUIRE(fin.rows[i].at("form") == row.at("form"));
        CHECK(fin.rows[i].at("status") == "ok");
        CHECK(std::stod(row.at("time_min_s")) <= std::stod(row.at("time_median_s")));
        CHECK(std::stod(row.at("time_median_s")) <= std::stod(row.at("time_max_s")));
        std::vector<long double> y;
        std::istringstream state(fin.rows[i].at("state"));
        for (std::string v; state >> v;)
            y.push_back(std::stold(v));
        std::array<long double, 3> w{};
        if (y.size() == 3) {
            w = {y[0], y[1], y[2]};
        } else if (row.at("form") == "body:quaternion" && y.size() == 7) {
            w = {y[4], y[5], y[6]}; // (qw, qx, qy, qz, omega1..3)
            ++quaternion;
        } else if (row.at("form").rfind("lagrangian", 0) == 0 && y.size() == 6) {
            w = omega_of(y);
            ++lagrangian;
            // the attitude is known there: a finite orientation error of the size of the error
            const double o = std::stod(row.at("orientation_error"));
            CHECK(o >= 0);
            CHECK(o < 1e-3);
        } else {
            continue;
        }
        const double at_end = double(distance(w, w_end) / scale);
        const double reported = std::stod(row.at("error"));
        CHECK(reported >= at_end * (1 - 1e-4) - 1e-16);
        ++checked;
    }
    CHECK(checked >= 15);
    CHECK(lagrangian >= 1);
    CHECK(quaternion >= 6);

    // issues 17 and 18: the split methods (on the body form with the quaternion) and the Taylor
    // method (on the scene's form) are rows like the others, their errors consistent with the
    // tolerance. Without a torque the free flows are exact and the split methods' step-doubling
    // estimate is rounding, so their steps double up to the span: the error is rounding whatever
    // the tolerance (observed 2.6e-14 .. 3.3e-13 for the three orders, in 104 .. 290 kicks); Taylor
    // follows its tolerance (observed 4.1e-5 at 1e-5, 2.3e-8 at 1e-8: sampled, calibrated per unit
    // step, whose error on this top is 0.84 .. 11 rtol: bench/results/proportionality.md).
    std::map<std::string, int> extra;
    for (const auto& row : csv.rows) {
        const std::string m = row.at("method");
        if (m.rfind("split", 0) != 0 && m != "taylor") continue;
        INFO(m << " tol " << row.at("tolerance") << " error " << row.at("error"));
        ++extra[m];
        const double tol = std::stod(row.at("tolerance")), err = std::stod(row.at("error"));
        CHECK(row.at("peer") == "rotgen");
        if (m == "taylor") {
            CHECK(row.at("form") == "body:omega");
            CHECK(err <= 20 * tol); // observed 4.1 tol
            CHECK(err >= tol / 5);  // observed 2.3 tol
        } else {
            CHECK(row.at("form") == "body:quaternion");
            CHECK(err < 1e-12);
            CHECK(std::stoul(row.at("rhs_evals")) <= 600); // steps doubling to the span
        }
    }
    CHECK(extra ==
          std::map<std::string, int>{{"split2", 2}, {"split4", 2}, {"split6", 2}, {"taylor", 2}});

    // issue 50: the summary ends with the choice in scene terms. At 1e-11, where no DOP853 run
    // gets, a split row (at rounding: observed split2 tol 1e-8, bench error 2.6e-14, run 1.7e-13)
    // is chosen, never long double (bench only); each printed scene block, run as a scene,
    // reproduces an error within its level (observed 4.2e-10 at 1e-3 .. 1.7e-13 at 1e-11); levels
    // below 3x the verifying reference's floor (1.45e-13 here) get no choice
    const std::vector<choice> choices = read_choices(r.out);
    REQUIRE(choices.size() >= 6);
    for (const choice& c : choices) {
        INFO(c.level << ": " << c.config);
        CHECK(c.config.find("long_double") == std::string::npos);
        CHECK(c.config.find("odeint") == std::string::npos);
        REQUIRE(c.lines.size() == 2);
        const double e = run_choice(scene, c.lines, dir);
        INFO("run: " << e);
        CHECK(e <= std::stod(c.level));
    }
    for (const choice& c : choices)
        if (c.level == "1e-11") CHECK(c.config.find("rotgen split") == 0);
    // the three tables agree: results.md's best table and its interpolated table name the choice
    for (const choice& c : choices) {
        INFO(c.level << ": " << c.config);
        CHECK(md.find("| " + c.level + " | " + c.config + " | ") != std::string::npos);
        if (c.config.find(" tol ") == std::string::npos) continue; // "dop853 fixed" curves
        const std::string curve = c.config.substr(0, c.config.rfind(" tol "));
        CHECK(md.find("| " + c.level + " | " + curve + " | ") != std::string::npos);
    }
    CHECK(md.find("| bench only |") != std::string::npos); // long double rows, the peers

    // one configuration re-run here: DOP853, rtol = atol = 1e-8, run-time parameters
    namespace model = rotgen::models::free_asymmetric_top_body;
    const auto sys = ROTGEN_GENERATED_SYSTEM(model, double);
    Eigen::Vector3d y(1.0, 0.1, 0.5);
    rotgen::dop853<double> method(1e-8, 1e-8);
    rotgen::error_layout layout; // the body form's omega: one rate group (tolerance_layout)
    layout.groups = {0, 0, 0};
    layout.span = 100;
    rotgen::calibrate(method, layout);
    const auto res = rotgen::integrate(sys, method, 0.0, y, 100.0); // to the end alone
    // the same steps sampled on their dense output (3 more RHS evaluations a step): what the bench
    // times and measures, as `simulate` runs it
    Eigen::Vector3d ys(1.0, 0.1, 0.5);
    long double sampled = 0;
    const auto res_sampled =
        rotgen::integrate(sys, method, 0.0, ys, sample_times(), [&](double t, const auto& x) {
            sampled =
                std::max(sampled, distance({x[0], x[1], x[2]}, exact((long double)t)) / scale);
        });
    REQUIRE(res_sampled.ok());
    CHECK(res_sampled.stats.steps == res.stats.steps);
    CHECK(res_sampled.stats.rhs_evals > res.stats.rhs_evals);
    REQUIRE(res.ok());
    bool found = false;
    for (std::size_t i = 0; i < csv.rows.size(); ++i) {
        const auto& row = csv.rows[i];
        if (row.at("method") != "dop853" || row.at("peer") != "rotgen" ||
            row.at("form") != "body:omega+runtime" || row.at("scalar") != "double" ||
            row.at("tolerance") != "1e-08")
            continue;
        found = true;
        // the row's run is the sampled one, dense output and all (before, the run to the end)
        CHECK(std::stoul(row.at("rhs_evals")) == res_sampled.stats.rhs_evals);
        std::istringstream state(fin.rows[i].at("state"));
        for (int k = 0; k < 3; ++k) {
            std::string v;
            state >> v;
            CHECK(std::stod(v) == Approx(y[k]).margin(1e-13));
        }
        const double at_end = double(distance({y[0], y[1], y[2]}, w_end) / scale);
        INFO("sampled here " << double(sampled) << ", at the end " << at_end);
        CHECK(std::stod(row.at("error")) == Approx(double(sampled)).epsilon(1e-4));
        // the scene tells the two measures apart: observed 4.35e-9 against 1.5e-9 at t = 100
        CHECK(sampled > 2 * at_end);
    }
    CHECK(found);

    // the long run: the midpoint rule conserves the quadratic invariant E of Euler's equations (to
    // its Newton tolerance, ~1e-15 per step); RK4 at the same step drifts
    const table drift = read_table(dir + "/drift.csv");
    REQUIRE(!drift.rows.empty());
    double midpoint = 0, rk4 = 0;
    for (const auto& row : drift.rows) {
        const double e = std::stod(row.at("relative_energy_error"));
        if (row.at("label").rfind("implicit_midpoint", 0) == 0) midpoint = std::max(midpoint, e);
        if (row.at("label").rfind("rk4", 0) == 0) rk4 = std::max(rk4, e);
    }
    CHECK(midpoint < 1e-10);
    CHECK(rk4 > 1000 * midpoint);
}

TEST_CASE("rotgen bench refuses bad arguments with a one-line message", "[bench]") {
    const std::string scene =
        std::string(ROTGEN_SOURCE_DIR) + "/models/scenes/free_top_workprecision.yaml";
    auto r = run_rotgen("bench");
    CHECK(r.status == 2);
    CHECK(r.err.find("bench needs a scene file") != std::string::npos);
    r = run_rotgen("bench '" + scene + "' --quik");
    CHECK(r.status == 2);
    CHECK(r.err.find("did you mean '--quick'?") != std::string::npos);
    r = run_rotgen("bench '" + scene + "' --long-steps -3");
    CHECK(r.status == 2);
    r = run_rotgen("bench '" + scene + "' -o /proc/no/such/dir");
    CHECK(r.status == 2);
    CHECK(r.err.find("/proc/no/such/dir") != std::string::npos);
    r = run_rotgen("bench /no/such/scene.yaml");
    CHECK(r.status == 2);
    // an explicit harness location that has none: refused, before any output
    const std::string no_out = std::string(ROTGEN_BINARY_DIR) + "/bench_no_tree_out";
    std::filesystem::remove_all(no_out);
    ::setenv("ROTGEN_SOURCE_DIR", "/proc/no/tree", 1); // inherited by the child only
    r = run_rotgen("bench '" + scene + "' -o '" + no_out + "'");
    ::unsetenv("ROTGEN_SOURCE_DIR");
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: ROTGEN_SOURCE_DIR=/proc/no/tree: not a rotgen source tree (no "
                   "bench/workprecision/harness.hpp and runtime/rotgen.hpp there)\n");
    CHECK_FALSE(std::filesystem::exists(no_out));
    // rates whose kinetic energy overflows double: refused at the `initial` key, nothing written
    const std::string dir = std::string(ROTGEN_BINARY_DIR) + "/bench_huge";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string huge = dir + "/huge.yaml";
    std::ofstream(huge) << ("model: " + std::string(ROTGEN_SOURCE_DIR) +
                            "/models/heavy_top.yaml\n"
                            "initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, "
                            "psi_dot: 1e200}\n"
                            "time: {start: 0, end: 1}\n");
    r = run_rotgen("bench '" + huge + "' -o '" + dir + "/out'");
    CHECK(r.status == 2);
    CHECK(r.err.find(huge + ":2:10: initial values too large for double precision: the kinetic "
                            "energy") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(std::filesystem::exists(dir + "/out/results.csv"));
}
