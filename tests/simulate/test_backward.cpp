// Backward time (issue 31): `time: {start: 10, end: 0}` runs every method backward, rows in run
// order; checked against the exact free top, against the forward run it retraces (a heavy top
// there and back with DOP853 and with a split method at a fixed step), and for events (`rising`
// means g increasing with t), the chart switch and the drifts.
#include "support.hpp"

#include <exact_free_top.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

using namespace rotgen::test;

namespace {

std::string scratch(const std::string& name) {
    return std::string(ROTGEN_BINARY_DIR) + "/" + name;
}

// Runs `rotgen simulate` on the scene text (model by path) into <name>.csv; `more` adds options.
csv_table simulate(const std::string& name, const std::string& text, const std::string& more = "",
                   std::string* out = nullptr) {
    const scratch_file scene(name + ".yaml", text);
    const run_result r =
        run_rotgen("simulate '" + scene.path + "' -o '" + scratch(name + ".csv") + "' " + more);
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    if (out) *out = r.out;
    return read_csv(scratch(name + ".csv"));
}

// max over the samples of |omega(t) - exact omega(t - t0)| for a free top with omega(t0) = w0.
double free_top_error(const csv_table& t, double t0, const std::array<double, 3>& w0) {
    const rotgen::free_top_exact<double> exact({1, 2, 3}, w0);
    double worst = 0;
    for (const auto& row : t.rows) {
        const auto w = exact(row[0] - t0);
        for (std::size_t k = 0; k < 3; ++k)
            worst =
                std::max(worst, std::abs(row[t.column("omega" + std::to_string(k + 1))] - w[k]));
    }
    return worst;
}

const std::string heavy_top = "model: " + model_path("heavy_top") + "\n";

} // namespace

TEST_CASE("the exact free top run backward from t = 100 to 0 equals the exact solution at every "
          "sample, for every method",
          "[simulate][backward]") {
    // Each method runs the same body forward 0 -> 100 and backward 100 -> 0 from the same omega;
    // both are compared with the exact solution (Jacobi elliptic functions) at their 1001 samples.
    // bound: 10x the larger error observed (forward, backward) for the method
    using row = std::tuple<std::string, double>;
    const auto [integrator, bound] = GENERATE(table<std::string, double>({
        row{"{method: dop853, rtol: 1e-10, atol: 1e-12}", 3e-9},    // observed 3.2e-10, 3.0e-10
        row{"{method: dopri5, rtol: 1e-10, atol: 1e-12}", 7e-9},    // observed 6.5e-10, 6.6e-10
        row{"{method: rk4, step: 0.01}", 5e-8},                     // observed 4.4e-9, 4.5e-9
        row{"{method: implicit_midpoint, step: 0.01}", 5e-3},       // observed 4.4e-4, 4.5e-4
        row{"{method: rosenbrock, rtol: 1e-8, atol: 1e-10}", 1e-7}, // observed 1.1e-8, 1.3e-8
        row{"{method: taylor, rtol: 1e-12, atol: 1e-14}", 3e-12},   // observed 2.4e-13, 1.8e-13
        row{"{method: split4, step: 0.01}", 3e-12},                 // observed 2.0e-13, 2.4e-13
    }));
    INFO(integrator);
    const std::array<double, 3> w0{0.05, 0.5, 1};
    const std::string body = "model: " + model_path("free_asymmetric_top") +
                             "\nform: body\ninitial: {phi: 0, theta: 0.5, psi: 0, omega1: 0.05, "
                             "omega2: 0.5, omega3: 1}\nintegrator: " +
                             integrator + "\nrecord: [omega1, omega2, omega3]\n";
    const csv_table fwd =
        simulate("backward_free_fwd", body + "time: {start: 0, end: 100, samples: 1001}\n");
    const csv_table back =
        simulate("backward_free_back", body + "time: {start: 100, end: 0, samples: 1001}\n");
    REQUIRE(back.rows.size() == 1001);
    // rows in run order: t from 100 down to 0
    CHECK(back.rows.front()[0] == 100.0);
    CHECK(back.rows.back()[0] == 0.0);
    for (std::size_t i = 1; i < back.rows.size(); ++i)
        CHECK(back.rows[i][0] < back.rows[i - 1][0]);
    const double e_fwd = free_top_error(fwd, 0, w0), e_back = free_top_error(back, 100, w0);
    INFO("forward " << e_fwd << ", backward " << e_back);
    CHECK(e_back < bound);
    CHECK(e_fwd < bound);
}

TEST_CASE("backward across theta ~ 0: the chart switch works as forward, on the exact solution",
          "[simulate][backward][gimbal]") {
    // The forward case (test_simulate.cpp) reversed: a Lagrangian run from t = 100 back to 0 that
    // passes close to theta = 0 changes to the body form and back, and stays on the exact free top.
    const csv_table t = [] {
        std::string out;
        const csv_table c =
            simulate("backward_tumble",
                     "model: " + model_path("free_asymmetric_top") +
                         "\nform: lagrangian\ninitial: {phi: 0, theta: 0.5, psi: 0, omega1: 0.05, "
                         "omega2: 0.5, omega3: 1}\ntime: {start: 100, end: 0, samples: 2001}\n"
                         "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}\n"
                         "record: [omega1, omega2, omega3, theta]\n",
                     "", &out);
        CHECK(out.find("switched to the body form at t = ") != std::string::npos);
        return c;
    }();
    const auto th = t.values("theta");
    CHECK(*std::min_element(th.begin(), th.end()) < 0.02); // it does pass close to theta = 0
    // observed 5.6e-10 (the forward run: 1.2e-9 from theta = 0.5, bound 4e-9)
    CHECK(free_top_error(t, 100, {0.05, 0.5, 1}) < 4e-9);
}

TEST_CASE("backward through theta = 1e-8: the chart switch keeps the run on the exact solution",
          "[simulate][backward][gimbal]") {
    // A free top with theta = 1e-8 at t = 50 (omega = w0 there) is run forward in the body form to
    // t = 100; from its state there a Lagrangian run goes back to t = 0, through theta ~ 1e-8 at
    // t = 50, where the Euler-angle chart loses its accuracy (phi_dot, psi_dot ~ 1/theta): the
    // switch to the body form and back keeps it on the exact free top. (The case above passes
    // theta = 0.004 only, where the Lagrangian form alone does as well.)
    const std::array<double, 3> w0{0.05, 0.5, 1};
    const std::string model = "model: " + model_path("free_asymmetric_top") + "\n";
    const csv_table there =
        simulate("backward_pole_there",
                 model + "form: body\ninitial: {phi: 0.4, theta: 1e-8, psi: 0.3, omega1: 0.05, "
                         "omega2: 0.5, omega3: 1}\ntime: {start: 50, end: 100, samples: 2}\n"
                         "integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}\n"
                         "record: [phi, theta, psi, omega1, omega2, omega3]\n");
    std::string initial;
    for (const char* c : {"phi", "theta", "psi", "omega1", "omega2", "omega3"}) {
        char value[40];
        std::snprintf(value, sizeof value, "%.17g", there.rows.back()[there.column(c)]);
        initial += std::string(initial.empty() ? "" : ", ") + c + ": " + value;
    }
    std::string out;
    const csv_table back = simulate("backward_pole",
                                    model + "form: lagrangian\ninitial: {" + initial +
                                        "}\ntime: {start: 100, end: 0, samples: 2001}\n"
                                        "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}\n"
                                        "record: [omega1, omega2, omega3, theta]\n",
                                    "", &out);
    INFO(out);
    CHECK(out.find("switched to the body form at t = ") != std::string::npos);
    const auto th = back.values("theta");
    CHECK(*std::min_element(th.begin(), th.end()) < 1e-7); // observed 9.9e-9, near t = 50
    // observed 2.7e-10; without the switch backward 7.5e-8 (the Lagrangian form through the pole)
    CHECK(free_top_error(back, 50, w0) < 2e-9);
}

TEST_CASE("a heavy top run forward 0 -> 2 and back 2 -> 0 recovers its initial state",
          "[simulate][backward]") {
    // DOP853 at rtol 1e-13 (the 1e-9), and a split method at a fixed step, which is
    // time-reversible: its step backward undoes its step forward but for rounding (1e-12). The
    // backward run continues from the forward run's CSV (--from).
    // bounds: the start recovered (observed 4.6e-13, 2.0e-15, 1.8e-15), the samples passed
    // through (observed 2.6e-13, 7.8e-16, 4.4e-16)
    using row = std::tuple<std::string, std::string, std::string, double, double>;
    const auto [form, integrator, record, bound, through_bound] =
        GENERATE(table<std::string, std::string, std::string, double, double>({
            row{"lagrangian", "{method: dop853, rtol: 1e-13, atol: 1e-13}",
                "[phi, theta, psi, phi_dot, theta_dot, psi_dot]", 4e-12, 2.5e-12},
            row{"body", "{method: split4, step: 0.01}", "[q0, q1, q2, q3, omega1, omega2, omega3]",
                2e-14, 7e-15},
            row{"body", "{method: split2, step: 0.01}", "[q0, q1, q2, q3, omega1, omega2, omega3]",
                1.8e-14, 4e-15},
        }));
    INFO(integrator);
    const std::string text = heavy_top + "form: " + form +
                             "\ninitial: {phi: 0.3, theta: 0.5, psi: 0.2, phi_dot: 1, theta_dot: "
                             "0.4, psi_dot: 30}\nintegrator: " +
                             integrator + "\nrecord: " + record + "\n";
    const csv_table fwd =
        simulate("there_" + form, text + "time: {start: 0, end: 2, samples: 11}\n");
    std::string out;
    const csv_table back =
        simulate("back_" + form, text + "time: {start: 2, end: 0, samples: 11}\n",
                 "--from '" + scratch("there_" + form + ".csv") + "'", &out);
    CHECK(out.find("start   from the last row of") != std::string::npos);
    REQUIRE(back.rows.front()[0] == 2.0);
    REQUIRE(back.rows.back()[0] == 0.0);
    double worst = 0;
    for (std::size_t c = 1; c < fwd.header.size(); ++c)
        worst = std::max(worst, std::abs(back.rows.back()[c] - fwd.rows.front()[c]));
    INFO("recovered to " << worst);
    CHECK(worst < bound);
    // the backward run passes through the forward run's samples
    for (std::size_t i = 0; i < 11; ++i)
        CHECK(std::abs(back.rows[i][1] - fwd.rows[10 - i][1]) < through_bound);
}

TEST_CASE("events keep their meaning in t backward: rising means g increasing with t",
          "[simulate][backward][events]") {
    // The heavy top's theta_dot rises through 0 at the top of each nod (theta minimal). The
    // backward run over the same stretch finds the same zeros with `rising`, in its own order
    // (t decreasing); a filter taken in the direction of the run would find the other turning
    // points instead.
    const std::string text = heavy_top +
                             "form: lagrangian\ninitial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, "
                             "theta_dot: 0.1, psi_dot: 30}\n"
                             "integrator: {method: dop853, rtol: 1e-12, atol: 1e-12}\n"
                             "record: [phi, theta, psi, phi_dot, theta_dot, psi_dot]\n"
                             "events: [{name: top, when: theta_dot, direction: rising}]\n";
    simulate("events_fwd", text + "time: {start: 0, end: 3, samples: 7}\n");
    simulate("events_back", text + "time: {start: 3, end: 0, samples: 7}\n",
             "--from '" + scratch("events_fwd.csv") + "'");
    const csv_table fwd = read_csv(scratch("events_fwd.events.csv"));
    const csv_table back = read_csv(scratch("events_back.events.csv"));
    REQUIRE(fwd.rows.size() >= 2);
    REQUIRE(back.rows.size() == fwd.rows.size());
    const std::size_t n = fwd.rows.size(), t = fwd.column("t"), th = fwd.column("theta");
    for (std::size_t i = 0; i < n; ++i) {
        CHECK(std::abs(back.rows[i][t] - fwd.rows[n - 1 - i][t]) < 1.2e-12); // observed 1.3e-13
        CHECK(std::abs(back.rows[i][th] - fwd.rows[n - 1 - i][th]) < 2e-12); // observed 2.0e-13
    }
    // at the top of a nod theta is at its minimum: below the start
    for (const auto& row : back.rows)
        CHECK(row[th] < 0.5);
}

TEST_CASE("a backward run's summary reports its span and drifts as a forward run's",
          "[simulate][backward]") {
    std::string out;
    simulate("backward_summary",
             heavy_top + "form: hamiltonian\ninitial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, "
                         "theta_dot: 0, psi_dot: 30}\ntime: {start: 10, end: 0, samples: 101}\n"
                         "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}\n"
                         "record: [theta, energy, p_phi]\n",
             "", &out);
    INFO(out);
    CHECK(out.find(", t 10.0 .. 0.0\n") != std::string::npos);
    const csv_table t = read_csv(scratch("backward_summary.csv"));
    double drift = 0;
    for (double e : t.values("energy"))
        drift = std::max(drift, std::abs(e - t.values("energy").front()));
    CHECK(drift < 3e-11); // observed 2.3e-12
    CHECK(out.find("drift   energy") != std::string::npos);
}

TEST_CASE("a zero time span is refused, and a backward scene by bench",
          "[simulate][backward][errors]") {
    const scratch_file scene(
        "zero_span.yaml",
        heavy_top + "initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}\n"
                    "time: {start: 1, end: 1}\n");
    const run_result r =
        run_rotgen("simulate '" + scene.path + "' -o '" + scratch("zero_span.csv") + "'");
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: " + scene.path +
                       ":3:23: time end must differ from time start (an end before the start "
                       "runs backward in time)\n");
    CHECK_FALSE(std::ifstream(scratch("zero_span.csv")).good());
    // bench measures forward runs only: refused before any work
    const scratch_file back(
        "bench_backward.yaml",
        heavy_top + "initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}\n"
                    "time: {start: 1, end: 0}\n");
    const run_result b =
        run_rotgen("bench '" + back.path + "' -o '" + scratch("bench_backward") + "'");
    CHECK(b.status == 2);
    CHECK(b.err == "rotgen: error: " + back.path +
                       ":3:23: bench measures forward runs: time end must be after time start "
                       "(simulate runs backward)\n");
    CHECK_FALSE(std::ifstream(scratch("bench_backward/results.csv")).good());
}
