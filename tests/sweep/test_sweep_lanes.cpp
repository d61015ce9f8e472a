// rotgen sweep --lanes W: members in SIMD batches against the scalar runs of the same members.
// - the batch kernel against the scalar kernel at random states (the only difference: xsimd's
//   vector sin and cos against libm's);
// - RK4 lanes take the scalar runs' steps and end within rounding of them, DOP853 lanes within the
//   tolerance; summary.csv has the same columns and rows;
// - a member the batch cannot carry (a start in the body form, a chart switch during the run, a
//   batch that fails at max_steps, a start that is a user error) gives the scalar run's row;
// - taylor lanes within the tolerance, the same bytes for -j 1 and -j 2;
// - events: the scalar runs' event times, a terminal event ending its own lane only, and a lane's
//   own steps and rhs_evals up to its end (RK4: its scalar run's; DOP853 and Taylor: the shared
//   steps until then);
// - the summary's lanes line: how many members ran in batches;
// - scenes lanes cannot run and bad --lanes values: one line, exit 2, nothing written.
#include "support.hpp"

#include "run/lanes.hpp"
#include "scene/scene.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <tuple>

using namespace rotgen;
using namespace rotgen::test;

namespace {

std::string scratch(const std::string& name) {
    return std::string(ROTGEN_BINARY_DIR) + "/" + name;
}

std::string heavy_top(const std::string& integrator, const std::string& rest) {
    return "model: " + model_path("heavy_top") +
           "\ninitial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}\n"
           "time: {end: 2, samples: 41}\nintegrator: " +
           integrator + "\nrecord: [theta, phi, energy, p_phi]\n" + rest;
}

std::string field(const std::string& line, std::size_t i) {
    std::istringstream in(line);
    std::string cell;
    for (std::size_t k = 0; k <= i; ++k)
        std::getline(in, cell, ',');
    return cell;
}

// summary.csv of the scene without and with --lanes W (exit status 0 or `status`), and the lanes
// run's summary line on lanes ("lanes   N of M members in batches of W (ARCH)", without its
// indent; empty if none).
struct summary_pair {
    std::string scalar, lanes, line;
};
summary_pair summaries(const scratch_file& scene, const std::string& name, int lanes,
                       int status = 0, const std::string& jobs = "2") {
    summary_pair out;
    for (int k = 0; k < 2; ++k) {
        const std::string dir = scratch(name + (k == 0 ? "_scalar" : "_lanes"));
        const test::run_result r =
            run_rotgen("sweep '" + scene.path + "' -o '" + dir + "' -j " + jobs +
                       (k == 0 ? std::string(" -q") : " --lanes " + std::to_string(lanes)));
        INFO(r.err);
        REQUIRE(r.status == status);
        (k == 0 ? out.scalar : out.lanes) = read_file(dir + "/summary.csv");
        for (const std::string& line : text_lines(r.out + r.err))
            if (k == 1 && line.rfind("  lanes   ", 0) == 0) out.line = line.substr(2);
    }
    return out;
}

// The summary's lanes line for `in` of `of` members in batches of `w`, on any target.
bool lanes_line_is(const std::string& line, std::size_t in, std::size_t of, int w) {
    const std::string head = "lanes   " + std::to_string(in) + " of " + std::to_string(of) +
                             " members in batches of " + std::to_string(w) + " (";
    return line == head + "avx2+fma)" || line == head + "avx512+fma)" || line == head + "sse2)";
}

// The `steps` and `rhs_evals` columns of the summary written by summaries(scene, name, ...) and
// its scalar twin: {scalar steps, lanes steps, scalar rhs_evals, lanes rhs_evals} per member.
std::vector<std::array<double, 4>> work_columns(const std::string& name) {
    const csv_table s = read_csv(scratch(name + "_scalar/summary.csv"));
    const csv_table l = read_csv(scratch(name + "_lanes/summary.csv"));
    std::vector<std::array<double, 4>> out;
    for (std::size_t m = 0; m < s.rows.size(); ++m)
        out.push_back({s.values("steps")[m], l.values("steps")[m], s.values("rhs_evals")[m],
                       l.values("rhs_evals")[m]});
    return out;
}

// The largest relative difference of the values of the columns `prefix`* (final.*: the last
// sample's; event.*: the events' first times) of the two summaries written by summaries(scene,
// name, ...), with the member, varied value and status columns equal.
double largest_difference(const std::string& name, const std::string& a, const std::string& b,
                          const std::string& prefix = "final.") {
    const csv_table s = read_csv(scratch(name + "_scalar/summary.csv"));
    const csv_table l = read_csv(scratch(name + "_lanes/summary.csv"));
    REQUIRE(s.header == l.header);
    REQUIRE(s.rows.size() == l.rows.size());
    double worst = 0;
    for (std::size_t m = 0; m < s.rows.size(); ++m)
        for (std::size_t c = 0; c < s.header.size(); ++c) {
            if (s.header[c].rfind(prefix, 0) != 0) continue;
            const double x = s.rows[m][c], y = l.rows[m][c];
            if (x == y) continue; // 0 for an event that did not occur (an empty cell)
            worst = std::max(worst, std::abs(x - y) / std::max(std::abs(x), 1e-300));
        }
    const auto a_lines = text_lines(a), b_lines = text_lines(b);
    for (std::size_t m = 1; m < a_lines.size(); ++m) {
        CHECK(field(a_lines[m], 0) == field(b_lines[m], 0)); // member
        CHECK(field(a_lines[m], 1) == field(b_lines[m], 1)); // the varied value
        CHECK(a_lines[m].substr(a_lines[m].rfind(',')) ==
              b_lines[m].substr(b_lines[m].rfind(','))); // status
    }
    return worst;
}

// The falling top's lanes (the events test below) share their steps: the members that reach the
// floor (0, 1, 2) report the shared steps until then, fewer than the batch's total that the
// others (3..7) report, and at least as many as their scalar runs (the batch's step is the
// smallest its lanes need); rhs_evals likewise.
void check_shared_work(const std::string& name) {
    const auto w = work_columns(name);
    REQUIRE(w.size() == 8);
    for (std::size_t m = 3; m < 8; ++m) {
        CHECK(w[m][1] == w[7][1]);
        CHECK(w[m][3] == w[7][3]);
    }
    for (std::size_t m = 0; m < 3; ++m) {
        INFO("member " << m);
        CHECK(w[m][1] < w[7][1]);
        CHECK(w[m][3] < w[7][3]);
        CHECK(w[m][1] >= w[m][0]);
        CHECK(w[m][3] >= w[m][2]);
    }
}

} // namespace

TEST_CASE("sweep --lanes: the batch kernel is the scalar kernel up to vector sin and cos",
          "[sweep][lanes]") {
    const scratch_file scene("lanes_kernel.yaml", heavy_top("{method: rk4, step: 0.01}", ""));
    stage_timings timings;
    const prepared_scene prepared(load_scene(scene.path), timings);
    const lane_kernels k = compile_lanes(prepared, timings, 4);
    const compiled_form& cf = prepared.compiled(form_kind::lagrangian, timings, nullptr);
    REQUIRE((k.width == 2 || k.width == 4));
    // the kernels read the prepared values w (the parameters, then the hoisted constants)
    const std::size_t lanes = 8, n = cf.sys.n, np = cf.f.parameters.size(), nw = cf.prepared_size();
    REQUIRE(nw > np); // the heavy top has constants (M g h, 1/I1, ...)
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> angle(0.05, 3.1), rate(-40, 40), positive(0.2, 3);
    double worst_ulps = 0;
    for (int round = 0; round < 200; ++round) {
        std::vector<double> y(n * lanes), w(nw * lanes), d(n * lanes);
        std::vector<std::vector<double>> wl(lanes, std::vector<double>(nw));
        for (std::size_t l = 0; l < lanes; ++l) {
            for (std::size_t c = 0; c < n; ++c)
                y[c * lanes + l] = c < 3 ? angle(rng) : rate(rng);
            std::vector<double> pl(np);
            for (double& v : pl)
                v = positive(rng);
            cf.prepare(pl.data(), wl[l].data());
            for (std::size_t j = 0; j < nw; ++j)
                w[j * lanes + l] = wl[l][j];
        }
        k.rhs(w.data(), 0.3, y.data(), d.data(), lanes);
        for (std::size_t l = 0; l < lanes; ++l) {
            std::vector<double> yl(n), dl(n);
            for (std::size_t c = 0; c < n; ++c)
                yl[c] = y[c * lanes + l];
            cf.sys.f(wl[l].data(), 0.3, yl.data(), dl.data());
            // in units of the last place of the largest rate of the lane: the rates are sums of
            // terms, so a 1-ulp change of sin theta moves a small sum by ulps of its terms
            double scale = 0;
            for (std::size_t c = 0; c < n; ++c)
                scale = std::max(scale, std::abs(dl[c]));
            const double ulp = std::nextafter(scale, 2 * scale) - scale;
            for (std::size_t c = 0; c < n; ++c)
                worst_ulps = std::max(worst_ulps, std::abs(d[c * lanes + l] - dl[c]) / ulp);
        }
    }
    // observed 45 ulps of the largest rate (15 before the lane kernels fused products into sums,
    // -ffp-contract=fast): xsimd's sin and cos (Cephes' polynomials; xsimd documents no bound)
    // differ from libm's by an ulp or so, and the rates are sums of terms several times larger
    // than the largest rate, carrying those ulps
    CHECK(worst_ulps <= 100);
}

TEST_CASE(
    "sweep --lanes: the batch taylor kernel says whether the coefficients it wrote are finite",
    "[sweep][lanes][taylor]") {
    const scratch_file scene("lanes_taylor_kernel.yaml",
                             heavy_top("{method: taylor, rtol: 1e-10, atol: 1e-10}", ""));
    stage_timings timings;
    const prepared_scene prepared(load_scene(scene.path), timings);
    const lane_kernels k = compile_lanes(prepared, timings, 8); // 8-wide where AVX-512 is
    REQUIRE(k.taylor != nullptr);
    const compiled_form& cf = prepared.compiled(form_kind::lagrangian, timings, nullptr);
    const std::size_t lanes = 8, n = cf.sys.n, np = cf.f.parameters.size();
    const int order = 13; // the order of rtol 1e-10 (taylor<double>::order_for)
    const std::size_t m = order + 1;
    // the kernel's answer and how many coefficients are not finite, lane 1 at theta1 and the
    // others at 0.5 (y = (phi, theta, psi, phi_dot, theta_dot, psi_dot), psi_dot = 30)
    const auto expand = [&](double theta1) {
        std::vector<double> c(n * m * lanes), p(np * lanes);
        for (std::size_t l = 0; l < lanes; ++l) {
            c[(1 * m) * lanes + l] = l == 1 ? theta1 : 0.5;
            c[(5 * m) * lanes + l] = 30;
            for (std::size_t j = 0; j < np; ++j)
                p[j * lanes + l] = cf.f.parameters[j].value;
        }
        const int finite = k.taylor(p.data(), 0, c.data(), order, lanes);
        const auto bad =
            std::count_if(c.begin(), c.end(), [](double v) { return !std::isfinite(v); });
        return std::make_pair(finite, bad);
    };
    const auto [finite, bad] = expand(0.5);
    CHECK(finite == 1);
    CHECK(bad == 0);
    // at theta = 0 the Lagrangian form divides by sin theta
    const auto [finite0, bad0] = expand(0.0);
    CHECK(finite0 == 0);
    CHECK(bad0 > 0);
}

TEST_CASE("sweep --lanes: rk4 lanes end within rounding of the scalar runs, dop853 lanes within "
          "the tolerance",
          "[sweep][lanes]") {
    const std::string vary = "sweep:\n  vary:\n    initial.theta: {from: 0.2, to: 1.4, count: 10}\n"
                             "    parameters.h: {values: [0.1, 0.3]}\n";
    {
        const scratch_file scene("lanes_rk4.yaml", heavy_top("{method: rk4, step: 0.01}", vary));
        const auto [scalar, lanes, line] = summaries(scene, "lanes_rk4", 4);
        CHECK(lanes_line_is(line, 20, 20, 4)); // every member ran in a batch
        REQUIRE(text_lines(scalar).size() == 21);
        for (const auto& w : work_columns("lanes_rk4")) { // the scalar runs' steps and evaluations
            CHECK(w[0] == w[1]);
            CHECK(w[2] == w[3]);
        }
        // observed 1.2e-15 after 200 steps (the ulps of sin and cos and of the fused products,
        // carried along; 5.6e-16 without fusing)
        CHECK(largest_difference("lanes_rk4", scalar, lanes) < 5e-15);
    }
    {
        const scratch_file scene("lanes_dop853.yaml",
                                 heavy_top("{method: dop853, rtol: 1e-8, atol: 1e-10}", vary));
        const auto [scalar, lanes, line] = summaries(scene, "lanes_dop853", 4);
        CHECK(lanes_line_is(line, 20, 20, 4));
        // observed 7.2e-9: rtol's scale (each run is within the tolerance of the true solution)
        CHECK(largest_difference("lanes_dop853", scalar, lanes) < 5e-8);
    }
}

TEST_CASE("sweep --lanes: taylor lanes agree with the scalar runs within the tolerance, the same "
          "for any -j",
          "[sweep][lanes][taylor]") {
    const std::string vary = "sweep:\n  vary:\n    initial.theta: {from: 0.2, to: 1.4, count: 10}\n"
                             "    parameters.h: {values: [0.1, 0.3]}\n";
    const scratch_file scene("lanes_taylor.yaml",
                             heavy_top("{method: taylor, rtol: 1e-10, atol: 1e-10}", vary));
    const auto [scalar, lanes, line] = summaries(scene, "lanes_taylor", 8);
    CHECK(lanes_line_is(line, 20, 20, 8));
    // observed 1.6e-11: each run within rtol 1e-10 of the true solution
    CHECK(largest_difference("lanes_taylor", scalar, lanes) < 1.6e-10);
    // the batch takes the smallest of its lanes' steps: never fewer than a member alone
    for (const auto& w : work_columns("lanes_taylor"))
        CHECK(w[1] >= w[0]);
    // threads take whole batches: one thread writes the same bytes
    const auto one = summaries(scene, "lanes_taylor_j1", 8, 0, "1");
    CHECK(one.lanes == lanes);
}

TEST_CASE("sweep --lanes: members a batch cannot carry give the scalar runs' rows",
          "[sweep][lanes]") {
    // member 1, without spin, swings through the pole (theta_dot -3: a chart switch at t = 0.1,
    // |sin theta| < 0.1), member 2 starts there (in the body form); both run alone, digit for
    // digit as without lanes
    const scratch_file chart(
        "lanes_chart.yaml",
        heavy_top("{method: rk4, step: 0.01}",
                  "sweep:\n  mode: zip\n  vary:\n    initial.theta: {values: [0.5, 0.3, 0.05, "
                  "0.6, 0.7]}\n    initial.theta_dot: {values: [0, -3, 0, 0, 0]}\n"
                  "    initial.psi_dot: {values: [30, 0, 30, 30, 30]}\n"));
    const auto [scalar, lanes, line] = summaries(chart, "lanes_chart", 4);
    CHECK(lanes_line_is(line, 3, 5, 4)); // members 1 and 2 ran alone
    const auto a = text_lines(scalar), b = text_lines(lanes);
    REQUIRE(a.size() == 6);
    CHECK(a[2] == b[2]);
    CHECK(a[3] == b[3]);
    // the three members in lanes differ from their runs alone by the lanes' rounding
    CHECK(largest_difference("lanes_chart", scalar, lanes) < 2e-15); // observed 2.0e-16
    // a fast member exhausts max_steps for its whole batch (one batch of 4): every lane reruns
    // alone; theta = 0 cannot start without the chart switch (a user error of that member)
    const scratch_file failing(
        "lanes_failing.yaml",
        heavy_top("{method: dop853, rtol: 1e-10, atol: 1e-12, max_steps: 400}",
                  "switch_chart: false\nsweep:\n  mode: zip\n  vary:\n    initial.theta: "
                  "{values: [0.5, 0, 0.6, 0.5]}\n    initial.psi_dot: {values: [30, 30, 30, "
                  "3000]}\n"));
    const auto [s2, l2, line2] = summaries(failing, "lanes_failing", 4, 3);
    CHECK(lanes_line_is(line2, 0, 4, 4));
    CHECK(s2 == l2);
    CHECK(text_lines(s2)[4].find("max_steps = 400 reached") != std::string::npos);
}

TEST_CASE("sweep --lanes: lanes find the scalar runs' events and a terminal one ends its lane only",
          "[sweep][lanes]") {
    // The falling top (models/scenes/falling_top.yaml): with psi_dot 0, 1, 2 it reaches the floor
    // (theta = pi/2, a terminal event) before t = 2.8; from 3 on it stays above it until t = 5.
    // One batch of 8 lanes holds both kinds.
    const auto scene_text = [](const std::string& integrator) {
        return "model: " + model_path("heavy_top") +
               "\ninitial: {phi: 0, theta: 0.3, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\n"
               "time: {end: 5, samples: 51}\nintegrator: " +
               integrator +
               "\nrecord: [theta, theta_dot, energy]\nevents:\n"
               "  - {name: halfway, when: theta - pi/4, direction: rising}\n"
               "  - {name: floor, when: theta - pi/2, direction: rising, action: stop}\n"
               "sweep:\n  vary:\n    initial.psi_dot: {values: [0, 1, 2, 3, 4, 6, 8, 10]}\n";
    };
    {
        const scratch_file scene("lanes_events_rk4.yaml", scene_text("{method: rk4, step: 0.01}"));
        const auto [scalar, lanes, line] = summaries(scene, "lanes_events_rk4", 8);
        CHECK(lanes_line_is(line, 8, 8, 8));
        // a lane's own steps and evaluations, up to its terminal event: its scalar run's
        for (const auto& w : work_columns("lanes_events_rk4")) {
            CHECK(w[0] == w[1]);
            CHECK(w[2] == w[3]);
        }
        const csv_table t = read_csv(scratch("lanes_events_rk4_lanes/summary.csv"));
        const std::vector<double> end = t.values("final.t"), floor = t.values("event.floor");
        CHECK(end[0] == floor[0]); // stopped at the floor: its state is the last row
        CHECK(end[0] < 2.5);
        CHECK(end[3] == 5); // never reached it
        CHECK(field(text_lines(lanes)[4], t.column("event.floor")).empty());
        // observed: the same event times, digit for digit (the same steps and interpolants up to
        // the ulps of the vector sin and cos), final values within 1.6e-15
        CHECK(largest_difference("lanes_events_rk4", scalar, lanes, "event.") < 1e-14);
        CHECK(largest_difference("lanes_events_rk4", scalar, lanes) < 2e-14);
    }
    {
        const scratch_file scene("lanes_events_dop853.yaml",
                                 scene_text("{method: dop853, rtol: 1e-12, atol: 1e-12}"));
        const auto [scalar, lanes, line] = summaries(scene, "lanes_events_dop853", 8);
        CHECK(lanes_line_is(line, 8, 8, 8));
        check_shared_work("lanes_events_dop853");
        // observed 7.8e-13 for the event times and 4.2e-10 for the final values (theta_dot at the
        // floor, where the runs' shared and own steps differ most)
        CHECK(largest_difference("lanes_events_dop853", scalar, lanes, "event.") < 8e-12);
        CHECK(largest_difference("lanes_events_dop853", scalar, lanes) < 4e-9);
    }
    {
        const scratch_file scene("lanes_events_taylor.yaml",
                                 scene_text("{method: taylor, rtol: 1e-12, atol: 1e-12}"));
        const auto [scalar, lanes, line] = summaries(scene, "lanes_events_taylor", 8);
        CHECK(lanes_line_is(line, 8, 8, 8));
        check_shared_work("lanes_events_taylor");
        // observed 4.9e-15 for the event times and 5.4e-12 for the final values
        CHECK(largest_difference("lanes_events_taylor", scalar, lanes, "event.") < 5e-14);
        CHECK(largest_difference("lanes_events_taylor", scalar, lanes) < 5e-11);
    }
}

TEST_CASE("sweep --lanes: what lanes cannot run is refused with one line, exit 2, no output",
          "[sweep][lanes][errors]") {
    using row = std::tuple<std::string, std::string, std::string>; // integrator+rest, option, msg
    const auto [scene_tail, option,
                message] = GENERATE(table<std::string, std::string, std::string>({
        row{"{method: dopri5}", "--lanes 4",
            "lanes_bad.yaml:4:13: --lanes needs the method rk4, dop853 or taylor, not dopri5 (or "
            "run the sweep without --lanes)"},
        row{"{method: rk4, step: 0.01}", "--lanes 0",
            "rotgen sweep: --lanes needs a whole number of lanes from 1 to 64, got '0'"},
        row{"{method: rk4, step: 0.01}", "--lanes four",
            "rotgen sweep: --lanes needs a whole number of lanes from 1 to 64, got 'four'"},
        row{"{method: rk4, step: 0.01}", "--lanes 65",
            "rotgen sweep: --lanes needs a whole number of lanes from 1 to 64, got '65'"},
        row{"{method: rk4, step: 0.01}", "--lanes -4",
            "rotgen sweep: --lanes needs a whole number of lanes from 1 to 64, got '-4'"},
        row{"{method: rk4, step: 0.01}", "-j -1",
            "rotgen sweep: -j needs a whole number of threads from 1 to 4096, got '-1'"},
        row{"{method: rk4, step: 0.01}", "-j --lanes 4", "rotgen sweep: -j needs a value (N)"},
    }));
    const scratch_file scene("lanes_bad.yaml",
                             heavy_top(scene_tail, "sweep:\n  vary:\n    initial.theta: {values: "
                                                   "[0.3, 0.4]}\n"));
    const std::string dir = scratch("lanes_bad_out");
    const test::run_result r = run_rotgen("sweep '" + scene.path + "' -o '" + dir + "' " + option);
    INFO(r.err);
    CHECK(r.status == 2);
    const std::string located = "rotgen: error: " + scratch(message) + "\n";
    const std::string unlocated = "rotgen: error: " + message + "\n";
    CHECK((r.err == located || r.err == unlocated));
    struct stat st {};
    CHECK(::stat(dir.c_str(), &st) != 0);
}

// Whether this CPU has what a `taylor` scene's 8-wide batch kernels need (host_lane_vector_flags).
bool cpu_has_avx512() {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
           __builtin_cpu_supports("fma");
#else
    return false;
#endif
}

// A `taylor` scene's lanes run 8-wide where the CPU has AVX-512 (on a CPU without it, this checks
// the AVX2 target only); ROTGEN_LANES_TARGET=avx2 keeps them 4-wide, to the same bytes; another
// value is refused.
TEST_CASE("sweep --lanes: a taylor scene's batches are AVX-512 where the CPU has it unless "
          "ROTGEN_LANES_TARGET=avx2",
          "[sweep][lanes][taylor]") {
    const std::string vary =
        "sweep:\n  vary:\n    initial.theta: {from: 0.2, to: 1.4, count: 16}\n";
    const scratch_file scene("lanes_target.yaml",
                             heavy_top("{method: taylor, rtol: 1e-10, atol: 1e-10}", vary));
    const auto run = [&](const std::string& name) {
        const std::string dir = scratch(name);
        const test::run_result r =
            run_rotgen("sweep '" + scene.path + "' -o '" + dir + "' -j 1 --lanes 8");
        std::string line;
        for (const std::string& l : text_lines(r.out + r.err))
            if (l.rfind("  lanes   ", 0) == 0) line = l.substr(2);
        return std::make_tuple(r, line, read_file(dir + "/summary.csv"));
    };
    const auto [wide, wide_line, wide_summary] = run("lanes_target_scalar");
    REQUIRE(wide.status == 0);
    if (cpu_has_avx512())
        CHECK(wide_line == "lanes   16 of 16 members in batches of 8 (avx512+fma)");
    else
        CHECK(lanes_line_is(wide_line, 16, 16, 8));
    ::setenv("ROTGEN_LANES_TARGET", "avx2", 1);
    const auto [narrow, narrow_line, narrow_summary] = run("lanes_target_lanes");
    ::setenv("ROTGEN_LANES_TARGET", "bogus", 1);
    const auto [bad, bad_line, bad_summary] = run("lanes_target_bad");
    ::unsetenv("ROTGEN_LANES_TARGET");
    REQUIRE(narrow.status == 0);
    CHECK(lanes_line_is(narrow_line, 16, 16, 8));
    CHECK(narrow_line.find("avx512") == std::string::npos); // avx2+fma (or sse2)
    // lane by lane the same operations, so the same bytes (observed; also for 1,024 heavy tops)
    CHECK(wide_summary == narrow_summary);
    CHECK(bad.status == 2);
    CHECK(bad.err == "rotgen: error: ROTGEN_LANES_TARGET=bogus: unknown lane target; use avx2 "
                     "(never AVX-512) or auto (the default)\n");
    struct stat st {};
    CHECK(::stat(scratch("lanes_target_bad").c_str(), &st) != 0);
}
