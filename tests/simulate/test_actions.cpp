// Events that act (scene/event_actions.hpp, run/actions.hpp): impulses, set values, time events
// and counts, against independent truth: the closed form of the free symmetric top between
// impulses, the exact free asymmetric top (runtime/exact_free_top.hpp) restarted from the state
// after an impulse, and what an impulse or a set must conserve.
#include "support.hpp"

#include <exact_free_top.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <fstream>
#include <sstream>
#include <tuple>

using namespace rotgen::test;

namespace {

std::string scratch(const std::string& name) {
    return std::string(ROTGEN_BINARY_DIR) + "/" + name;
}

// The events CSV's text fields: event name and phase per row (read_csv reads numbers only).
std::vector<std::pair<std::string, std::string>> names_and_phases(const std::string& path) {
    std::vector<std::pair<std::string, std::string>> out;
    bool header = false;
    for (const std::string& line : text_lines(read_file(path))) {
        if (line.empty() || line[0] == '#') continue;
        if (!header) {
            header = true;
            continue;
        }
        std::istringstream in(line);
        std::string name, t, phase;
        std::getline(in, name, ',');
        std::getline(in, t, ',');
        std::getline(in, phase, ',');
        out.emplace_back(name, phase);
    }
    return out;
}

// The free symmetric top I = (I1, I1, I3) from omega(t0) over [t0, t]: omega3 constant,
// omega1 + i omega2 turning at Omega = (I3 - I1) omega3 / I1 (Euler's equations, 5.87-5.89).
std::array<double, 3> symmetric_top(double I1, double I3, std::array<double, 3> w, double dt) {
    const double Omega = (I3 - I1) * w[2] / I1;
    const std::complex<double> z = std::complex<double>(w[0], w[1]) * std::polar(1.0, Omega * dt);
    return {z.real(), z.imag(), w[2]};
}

const char* symmetric_model = "model:\n  name: kicked_symmetric_top\n"
                              "  parameters: {I1: 2, I3: 0.5, kick: 0.05}\n"
                              "  inertia: [I1, I1, I3]\n";

} // namespace

TEST_CASE("a free symmetric top kicked every 0.9 and set once follows the closed form piecewise",
          "[simulate][actions]") {
    const std::string method = GENERATE(as<std::string>{}, "dop853", "taylor");
    const scratch_file scene(
        "kicked_" + method + ".yaml",
        std::string(symmetric_model) +
            "form: body\ninitial: {phi: 0.1, theta: 0.7, psi: 0.2, omega1: 0.3, omega2: -0.1, "
            "omega3: 4}\ntime: {end: 3, samples: 301}\n"
            "integrator: {method: " +
            method +
            ", rtol: 1e-12, atol: 1e-14}\nrecord: [omega1, omega2, omega3, energy]\n"
            "events:\n"
            "  - {name: pulse, every: 0.9, action: {impulse: [kick, 2*kick, 3*kick]}}\n"
            "  - {name: nudge, when: t - 1.305, action: {set: {omega1: omega1 + 0.2}}}\n"
            "  - {name: cross, when: omega3 - 4.1}\n"); // jumped across by the first pulse
    const std::string csv = scratch("kicked_" + method + ".csv");
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    // the closed form: between actions, the turn; at 0.9 k an impulse I^-1 J, at 1.305 omega1 + 0.2
    const double I1 = 2, I3 = 0.5, kick = 0.05;
    const std::vector<double> at = {0.9, 1.305, 1.8, 2.7};
    const csv_table t = read_csv(csv);
    REQUIRE(t.rows.size() == 301);
    double worst = 0;
    for (const auto& row : t.rows) {
        std::array<double, 3> w = {0.3, -0.1, 4};
        double from = 0;
        for (double ta : at) {
            if (ta > row[0]) break;
            w = symmetric_top(I1, I3, w, ta - from);
            from = ta;
            if (ta == 1.305)
                w[0] += 0.2;
            else
                w = {w[0] + kick / I1, w[1] + 2 * kick / I1, w[2] + 3 * kick / I3};
        }
        w = symmetric_top(I1, I3, w, row[0] - from);
        for (int k = 0; k < 3; ++k)
            worst = std::max(worst, std::abs(row[1 + k] - w[static_cast<std::size_t>(k)]));
    }
    // measured 8.7e-13 (dop853) and 4.6e-14 (taylor)
    CHECK(worst < 5e-12);
    // a sample at an action's time shows the state after it: at t = 0.9, omega3 = 4 + 3 kick / I3
    CHECK(std::abs(t.rows[90][3] - (4 + 3 * kick / I3)) < 1e-13);
    const auto ev = names_and_phases(scratch("kicked_" + method + ".events.csv"));
    REQUIRE(ev.size() == 8);
    CHECK(ev[0] == std::make_pair(std::string("pulse"), std::string("before")));
    CHECK(ev[1] == std::make_pair(std::string("pulse"), std::string("after")));
    CHECK(ev[2].first == "nudge");
    CHECK(r.out.find("acted 3 times") != std::string::npos);
    // omega3 jumps across 4.1 at the first pulse: not a zero along the motion, not an event
    CHECK(r.out.find("event   cross: 0 times") != std::string::npos);
    CHECK(r.out.find("max over 5 segments") != std::string::npos);
}

TEST_CASE("after an impulse at a when-event the free asymmetric top is the exact solution "
          "started from the state after it",
          "[simulate][actions]") {
    const std::string form = GENERATE(as<std::string>{}, "body", "lagrangian");
    const scratch_file scene(
        "impulse_exact_" + form + ".yaml",
        "model:\n  name: kicked_asymmetric_top\n  inertia: [1, 2, 3]\nform: " + form +
            "\ninitial: {phi: 0.3, theta: 1.1, psi: 0.4, omega1: 0.05, omega2: 0.5, omega3: 1}\n"
            "time: {end: 20, samples: 401}\n"
            "integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}\n"
            "record: [omega1, omega2, omega3]\n"
            "events:\n  - {name: kick, when: omega2 - 0.2, direction: falling, after: 2,\n"
            "     action: {impulse: [0.1, -0.2, 0.3]}}\n");
    const std::string csv = scratch("impulse_exact_" + form + ".csv");
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const csv_table ev = read_csv(scratch("impulse_exact_" + form + ".events.csv"));
    // from the 2nd falling zero of omega2 - 0.2 on (after: 2): the 2nd, 3rd, 4th, a before and an
    // after row each
    REQUIRE(ev.rows.size() == 6);
    const std::array<double, 3> I = {1, 2, 3}, J = {0.1, -0.2, 0.3};
    std::vector<double> starts = {0};
    std::vector<rotgen::free_top_exact<double>> pieces = {
        rotgen::free_top_exact<double>(I, {0.05, 0.5, 1})};
    for (std::size_t a = 0; a < ev.rows.size(); a += 2) {
        const std::vector<double>&before = ev.rows[a], &after = ev.rows[a + 1];
        CHECK(after[1] == before[1]);
        // omega2 = 0.2 at the event on the exact solution (measured 9.4e-16 .. 7.1e-13)
        CHECK(std::abs(pieces.back()(before[1] - starts.back())[1] - 0.2) < 5e-12);
        std::array<double, 3> w{};
        for (std::size_t k = 0; k < 3; ++k) {
            w[k] = after[3 + k];
            // Delta omega = I^-1 J, to rounding (measured 0 .. 9.7e-17)
            CHECK(std::abs(w[k] - before[3 + k] - J[k] / I[k]) < 1e-15);
        }
        starts.push_back(before[1]);
        pieces.emplace_back(I, w);
    }
    double worst = 0;
    for (const auto& row : read_csv(csv).rows) {
        std::size_t p = starts.size() - 1;
        while (starts[p] > row[0])
            --p;
        const auto w = pieces[p](row[0] - starts[p]);
        for (std::size_t k = 0; k < 3; ++k)
            worst = std::max(worst, std::abs(row[1 + k] - w[k]));
    }
    // measured 1.6e-12 (body), 2.9e-12 (lagrangian)
    CHECK(worst < 3e-11);
}

TEST_CASE("an impulse along L changes |L| by |J| and keeps its direction", "[simulate][actions]") {
    // L in space axes is constant for a free body; the impulse_space below is 0.25 along it
    const std::string start = "{phi: 0.3, theta: 1.1, psi: 0.4, omega1: 0.2, omega2: 0.5, "
                              "omega3: 1}";
    const std::string model = "model:\n  name: free_tri\n  inertia: [1, 2, 3]\nform: body\n";
    const scratch_file probe("along_probe.yaml",
                             model + "initial: " + start +
                                 "\ntime: {end: 1, samples: 2}\nrecord: [Lx, Ly, Lz]\n");
    REQUIRE(run_rotgen("simulate '" + probe.path + "' -o '" + scratch("along_probe.csv") + "'")
                .status == 0);
    const std::vector<double> probe_row = read_csv(scratch("along_probe.csv")).rows.at(0);
    const std::vector<double> L0(probe_row.begin() + 1, probe_row.end());
    const double n0 = std::sqrt(L0[0] * L0[0] + L0[1] * L0[1] + L0[2] * L0[2]);
    std::ostringstream j;
    j.precision(17);
    j << "[" << 0.25 * L0[0] / n0 << ", " << 0.25 * L0[1] / n0 << ", " << 0.25 * L0[2] / n0 << "]";
    const scratch_file scene("along.yaml",
                             model + "initial: " + start +
                                 "\ntime: {end: 4, samples: 41}\n"
                                 "integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}\n"
                                 "record: [Lx, Ly, Lz]\nevents:\n"
                                 "  - {name: push, when: t - 1.55, action: {impulse_space: " +
                                 j.str() + "}}\n");
    const run_result r =
        run_rotgen("simulate '" + scene.path + "' -o '" + scratch("along.csv") + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    double worst_norm = 0, worst_direction = 0;
    for (const auto& row : read_csv(scratch("along.csv")).rows) {
        const double n = std::sqrt(row[1] * row[1] + row[2] * row[2] + row[3] * row[3]);
        const double expected = row[0] < 1.55 ? n0 : n0 + 0.25;
        worst_norm = std::max(worst_norm, std::abs(n - expected));
        for (int k = 0; k < 3; ++k)
            worst_direction = std::max(worst_direction, std::abs(row[1 + k] / n - L0[k] / n0));
    }
    // measured 5.1e-13 and 4.4e-13: the attitude's integration error (L = R(q) I omega)
    CHECK(worst_norm < 5e-12);
    CHECK(worst_direction < 5e-12);
    // at the action itself: |L| grows by |J| (measured 4.4e-16), the direction stays (measured
    // 1.9e-15: J is along L(0), which the run keeps to 4e-13)
    const csv_table ev = read_csv(scratch("along.events.csv"));
    REQUIRE(ev.rows.size() == 2);
    const auto norm = [](const std::vector<double>& r) {
        return std::sqrt(r[3] * r[3] + r[4] * r[4] + r[5] * r[5]);
    };
    CHECK(std::abs(norm(ev.rows[1]) - norm(ev.rows[0]) - 0.25) < 4e-15);
    for (std::size_t k = 3; k < 6; ++k)
        CHECK(std::abs(ev.rows[1][k] / norm(ev.rows[1]) - ev.rows[0][k] / norm(ev.rows[0])) <
              2e-14);
}

TEST_CASE("a set that flips omega3 keeps a free symmetric top's energy", "[simulate][actions]") {
    const scratch_file scene(
        "flip.yaml", std::string(symmetric_model) +
                         "form: lagrangian\ninitial: {phi: 0.1, theta: 0.7, psi: 0.2, omega1: 0.3, "
                         "omega2: -0.1, omega3: 4}\ntime: {end: 2, samples: 21}\n"
                         "integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}\n"
                         "record: [omega3, energy]\nevents:\n"
                         "  - {name: flip, when: t - 0.75, action: {set: {omega3: -omega3}}}\n");
    const run_result r =
        run_rotgen("simulate '" + scene.path + "' -o '" + scratch("flip.csv") + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const csv_table ev = read_csv(scratch("flip.events.csv"));
    REQUIRE(ev.rows.size() == 2);
    CHECK(ev.rows[1][3] == Approx(-ev.rows[0][3]).epsilon(1e-15));
    const double e0 = read_csv(scratch("flip.csv")).rows[0][2];
    double worst = 0;
    for (const auto& row : read_csv(scratch("flip.csv")).rows)
        worst = std::max(worst, std::abs(row[2] - e0));
    CHECK(std::abs(ev.rows[1][4] - ev.rows[0][4]) < 1e-14); // measured 8.9e-16
    CHECK(worst < 1e-12);                                   // measured 1.2e-13
    CHECK(r.out.find("max over 2 segments") != std::string::npos);
}

TEST_CASE("bad actions: exit 2, one line naming file and place, nothing written",
          "[simulate][actions][errors]") {
    using row = std::tuple<std::string, std::string, std::string>;
    const auto [name, events, expected] = GENERATE(table<std::string, std::string, std::string>({
        row{"every with when", "  - {name: a, when: t - 1, every: 0.5}\n",
            ":9:35: event 'a': give 'when' or 'every', not both"},
        row{"after 0", "  - {name: a, when: t - 1, after: 0}\n",
            ":9:35: event 'a': 'after' must be a whole number >= 1 (got '0')"},
        row{"unknown name", "  - {name: a, when: t - 1, action: {set: {omega4: 1}}}\n",
            ":9:43: event 'a': cannot set 'omega4'"},
        row{"two ways of one",
            "  - {name: a, when: t - 1, action: {set: {omega1: 1, theta_dot: 2}}}\n",
            ":9:54: event 'a': 'theta_dot' is a second way of giving the angular velocity"},
        row{"impulse of length 2", "  - {name: a, every: 1, action: {impulse: [1, 2]}}\n",
            ":9:43: event 'a': an impulse has 3 components [J1, J2, J3] (got 2)"},
        row{"unknown parameter", "  - {name: a, every: 1, action: {set: {parameters.zz: 1}}}\n",
            ":9:40: event 'a': the model has no parameter 'zz'"},
        row{"a parameter of the inertia",
            "  - {name: a, every: 1, action: {set: {parameters.I3: 1}}}\n",
            ":9:40: event 'a': cannot set parameters.I3: the inertia depends on it"},
        row{"a record name in a value",
            "  - {name: a, every: 1, action: {set: {omega1: energy}}}\n",
            "unknown symbol 'energy'"},
        row{"every not positive", "  - {name: a, every: -kick}\n",
            ":9:22: event 'a': 'every' must be a period > 0"},
    }));
    INFO(name);
    const scratch_file scene("bad_action.yaml",
                             std::string(symmetric_model) +
                                 "form: body\ninitial: {phi: 0, theta: 0.5, psi: 0, omega1: 0, "
                                 "omega2: 0, omega3: 1}\ntime: {end: 2}\nevents:\n" +
                                 events);
    const std::string out = scratch("bad_action.csv");
    std::remove(out.c_str());
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + out + "'");
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("rotgen: error: " + scene.path) == 0);
    CHECK(r.err.find(expected) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(std::ifstream(out).good());
}

TEST_CASE("actions in a backward run are refused, a non-unit quaternion stops the run",
          "[simulate][actions][errors]") {
    const std::string head = std::string(symmetric_model) +
                             "form: body\ninitial: {phi: 0, theta: 0.5, psi: 0, omega1: 0, "
                             "omega2: 0, omega3: 1}\n";
    const scratch_file back("back_action.yaml",
                            head + "time: {start: 2, end: 0}\nevents:\n"
                                   "  - {name: a, when: t - 1, action: {impulse: [0, 0, 1]}}\n");
    const run_result b =
        run_rotgen("simulate '" + back.path + "' -o '" + scratch("back_action.csv") + "'");
    CHECK(b.status == 2);
    CHECK(b.err == "rotgen: error: " + back.path +
                       ":9:36: event 'a': actions and time events are refused in a backward run "
                       "(time end before start)\n");
    const scratch_file quat("quat_action.yaml",
                            head + "time: {end: 2, samples: 5}\nevents:\n"
                                   "  - {name: a, when: t - 1.2, action: {set: {q0: 2}}}\n");
    const std::string out = scratch("quat_action.csv");
    const run_result q = run_rotgen("simulate '" + quat.path + "' -o '" + out + "'");
    INFO(q.out << q.err);
    CHECK(q.status == 3);
    CHECK(q.err.find(quat.path + ":9:45: event 'a': the quaternion set has norm") !=
          std::string::npos);
    CHECK(read_csv(scratch("quat_action.partial.csv")).rows.size() == 3); // t = 0, 0.5, 1
}

TEST_CASE("every counts from the scene's own start, also after --from", "[simulate][actions]") {
    const scratch_file model("every_model.yaml",
                             "name: every_top\nparameters: {I1: 2, I3: 0.5, kick: 0.05}\n"
                             "inertia: [I1, I1, I3]\n");
    const auto scene = [&](const std::string& end) {
        return "model: every_model.yaml\nform: body\ninitial: {phi: 0.1, theta: 0.7, psi: 0.2, "
               "omega1: 0.3, omega2: -0.1, omega3: 4}\ntime: {start: 0.1, end: " +
               end +
               ", samples: 10}\nrecord: [omega3, q0, q1, q2, q3, omega1, omega2]\nevents:\n"
               "  - {name: pulse, every: 0.4, action: {impulse: [0, 0, kick]}}\n";
    };
    const scratch_file first("every_first.yaml", scene("1"));
    REQUIRE(
        run_rotgen("simulate '" + first.path + "' -o '" + scratch("every_1.csv") + "' -q").status ==
        0);
    const scratch_file second("every_second.yaml", scene("2"));
    const run_result r =
        run_rotgen("simulate '" + second.path + "' --from '" + scratch("every_1.csv") + "' -o '" +
                   scratch("every_2.csv") + "' -q");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const csv_table a = read_csv(scratch("every_1.events.csv")),
                    b = read_csv(scratch("every_2.events.csv"));
    REQUIRE(a.rows.size() == 4);
    REQUIRE(b.rows.size() == 4);
    // 0.1 + 0.4 k: 0.5 and 0.9, then (from t = 1) 1.3 and 1.7, not 1.4 and 1.8
    CHECK(a.rows[0][1] == Approx(0.5).epsilon(1e-15));
    CHECK(a.rows[2][1] == Approx(0.9).epsilon(1e-15));
    CHECK(b.rows[0][1] == Approx(1.3).epsilon(1e-15));
    CHECK(b.rows[2][1] == Approx(1.7).epsilon(1e-15));
    // omega3 steps by kick / I3 = 0.1 at each (a free symmetric top keeps omega3 between)
    CHECK(read_csv(scratch("every_2.csv")).rows.back()[1] == Approx(4.4).epsilon(1e-13));
}

TEST_CASE("a sweep over the pulse strength varies the impulse and counts the actions",
          "[simulate][actions][sweep]") {
    const scratch_file scene(
        "sweep_kick.yaml",
        std::string(symmetric_model) +
            "form: body\ninitial: {phi: 0.1, theta: 0.7, psi: 0.2, omega1: 0.3, omega2: -0.1, "
            "omega3: 4}\ntime: {end: 2, samples: 5}\nrecord: [omega3]\nevents:\n"
            "  - {name: pulse, every: 0.6, action: {impulse: [0, 0, kick]}}\n"
            "  - {name: mark, when: t - 0.3}\n");
    const std::string dir = scratch("sweep_kick");
    std::filesystem::remove_all(dir);
    const run_result r =
        run_rotgen("sweep '" + scene.path + "' -o '" + dir + "' --vary parameters.kick=0:0.2:3 -q");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const csv_table s = read_csv(dir + "/summary.csv");
    REQUIRE(s.rows.size() == 3);
    for (std::size_t m = 0; m < 3; ++m) {
        const double kick = 0.1 * double(m);
        CHECK(s.rows[m][s.column("parameters.kick")] == Approx(kick).margin(1e-15));
        CHECK(s.rows[m][s.column("actions.pulse")] == 3); // at 0.6, 1.2, 1.8
        CHECK(s.rows[m][s.column("event.pulse")] == Approx(0.6).epsilon(1e-15));
        CHECK(s.rows[m][s.column("event.mark")] == Approx(0.3).epsilon(1e-13));
        // omega3 + 3 kick / I3, exactly but for rounding (measured 0 .. 9e-16)
        CHECK(std::abs(s.rows[m][s.column("final.omega3")] - (4 + 3 * kick / 0.5)) < 1e-14);
    }
}

TEST_CASE("a set of a parameter switches a torque law's sign", "[simulate][actions]") {
    // a symmetric top with the body torque k about its axis: I3 omega3' = k (5.89 with I1 = I2),
    // so omega3 rises at k / I3 until the set at t = 1 makes k = -k, then falls at the same rate
    const scratch_file scene(
        "switch_k.yaml",
        "model:\n  name: torqued_top\n  parameters: {I1: 2, I3: 0.5, k: 0.2}\n"
        "  inertia: [I1, I1, I3]\n  torque: [\"0\", \"0\", \"k\"]\n"
        "form: body\ninitial: {phi: 0.1, theta: 0.7, psi: 0.2, omega1: 0.3, omega2: -0.1, "
        "omega3: 4}\ntime: {end: 2, samples: 21}\n"
        "integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}\nrecord: [omega3]\n"
        "events:\n  - {name: mode, when: t - 1, action: {set: {parameters.k: -k}}}\n");
    const run_result r =
        run_rotgen("simulate '" + scene.path + "' -o '" + scratch("switch_k.csv") + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    double worst = 0;
    for (const auto& row : read_csv(scratch("switch_k.csv")).rows) {
        const double t = row[0], w3 = t <= 1 ? 4 + 0.4 * t : 4.4 - 0.4 * (t - 1);
        worst = std::max(worst, std::abs(row[1] - w3));
    }
    CHECK(worst < 1e-14); // measured 1.3e-15
}

TEST_CASE("sweep --lanes: a member whose event acts leaves its batch and runs alone",
          "[simulate][actions][sweep]") {
    // the kick comes at t = 0.9 + 10 kick: inside the span (end 2) for kick <= 0.1, so of the five
    // members (kick 0, 0.05, .., 0.2) three act and leave their batch, two stay in lanes
    const scratch_file scene(
        "lanes_kick.yaml",
        std::string(symmetric_model) +
            "form: body\ninitial: {phi: 0.1, theta: 0.7, psi: 0.2, omega1: 0.3, omega2: -0.1, "
            "omega3: 4}\ntime: {end: 2, samples: 5}\nintegrator: {method: rk4, step: 0.01}\n"
            "record: [omega3]\nevents:\n"
            "  - {name: pulse, when: t - 0.9 - 10*kick, action: {impulse: [0, 0, kick]}}\n");
    const std::string lanes = scratch("lanes_kick"), alone = scratch("lanes_kick_alone");
    std::filesystem::remove_all(lanes);
    std::filesystem::remove_all(alone);
    const std::string sweep = "sweep '" + scene.path + "' --vary parameters.kick=0:0.2:5 -o '";
    const run_result r = run_rotgen(sweep + lanes + "' --lanes 4");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("lanes   2 of 5 members") != std::string::npos);
    REQUIRE(run_rotgen(sweep + alone + "' -q").status == 0);
    const auto with_lanes = read_csv(lanes + "/summary.csv"),
               without = read_csv(alone + "/summary.csv");
    const std::size_t w3 = with_lanes.column("final.omega3"),
                      acted = with_lanes.column("actions.pulse");
    REQUIRE(with_lanes.rows.size() == 5);
    double worst = 0;
    for (std::size_t m = 0; m < 5; ++m) {
        const double kick = 0.05 * static_cast<double>(m);
        CHECK(with_lanes.rows[m][acted] == (kick <= 0.1 ? 1 : 0));
        // omega3 jumps by kick / I3 (I3 = 0.5) where the member acts, else stays 4; as alone
        const double expected = 4 + (kick <= 0.1 ? kick / 0.5 : 0);
        worst = std::max({worst, std::abs(with_lanes.rows[m][w3] - expected),
                          std::abs(with_lanes.rows[m][w3] - without.rows[m][w3])});
    }
    CHECK(worst < 4e-15); // measured 0: the body form keeps omega3 exactly between kicks
}

TEST_CASE("an event whose expression an action leaves at 0 is not reported there again",
          "[simulate][actions]") {
    // omega3 = 4 + 0.4 t crosses 4.3 at t = 0.75, where the action sets it to 4.3: g = 0 right
    // after the action, and the run goes on with g > 0, without firing again
    const scratch_file scene(
        "hold.yaml",
        "model:\n  name: torqued_top\n  parameters: {I1: 2, I3: 0.5, k: 0.2}\n"
        "  inertia: [I1, I1, I3]\n  torque: [\"0\", \"0\", \"k\"]\n"
        "form: body\ninitial: {phi: 0.1, theta: 0.7, psi: 0.2, omega1: 0.3, omega2: -0.1, "
        "omega3: 4}\ntime: {end: 2, samples: 21}\nrecord: [omega3]\n"
        "events:\n  - {name: hold, when: omega3 - 4.3, action: {set: {omega3: 4.3}}}\n");
    const run_result r =
        run_rotgen("simulate '" + scene.path + "' -o '" + scratch("hold.csv") + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("event   hold: 1 time, acted 1 time") != std::string::npos);
    const csv_table ev = read_csv(scratch("hold.events.csv"));
    REQUIRE(ev.rows.size() == 2);
    CHECK(ev.rows[0][1] == Approx(0.75).epsilon(1e-12));
    CHECK(read_csv(scratch("hold.csv")).rows.back()[1] == Approx(4.3 + 0.4 * 1.25).epsilon(1e-12));
}

TEST_CASE("an impulse on a gyrostat changes omega by I^-1 J and keeps the wheel's momentum",
          "[simulate][actions][wheels]") {
    // principal moments 2, 3, 4 without the wheel's axial moment, a free wheel on axis 2 with
    // p_wheel = 1.5: total L = I omega + h, h = p_wheel e2; an impulse J changes L by J while the
    // wheel keeps p_wheel, so omega jumps by I^-1 J = (0.05, -0.2/3, 0.075)
    const std::string model = "model:\n  name: kicked_gyrostat\n"
                              "  parameters: {I1: 2, I2: 3, I3: 4, Jw: 0.1}\n"
                              "  inertia: [I1, I2, I3]\n"
                              "  wheels: [{name: wheel, axis: [0, 1, 0], inertia: Jw}]\n";
    const std::string rest =
        "initial: {phi: 0.2, theta: 1.1, psi: 0.3, omega1: 0.3, omega2: 1, omega3: 0.2, "
        "p_wheel: 1.5}\ntime: {end: 2, samples: 21}\n"
        "integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}\n"
        "record: [omega1, omega2, omega3, p_wheel, Lx, Ly, Lz]\nevents:\n"
        "  - {name: kick, when: t - 1.05, action: {impulse: [0.1, -0.2, 0.3]}}\n";
    for (const std::string form : {"lagrangian", "body"}) {
        const scratch_file scene("gyrostat_kick_" + form + ".yaml",
                                 model + "form: " + form + "\n" + rest);
        const std::string out = scratch("gyrostat_kick_" + form + ".csv");
        const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + out + "'");
        INFO(form << ": " << r.out << r.err);
        REQUIRE(r.status == 0);
        const csv_table ev = read_csv(scratch("gyrostat_kick_" + form + ".events.csv"));
        REQUIRE(ev.rows.size() == 2); // before, after (columns from 3: the records)
        const std::vector<double>&before = ev.rows[0], &after = ev.rows[1];
        const double jump[3] = {0.1 / 2, -0.2 / 3, 0.3 / 4};
        double worst_omega = 0, dL2 = 0;
        for (int k = 0; k < 3; ++k) {
            worst_omega = std::max(worst_omega, std::abs(after[3 + k] - before[3 + k] - jump[k]));
            dL2 += (after[7 + k] - before[7 + k]) * (after[7 + k] - before[7 + k]);
        }
        CHECK(worst_omega < 2e-15);                                // measured 2.1e-16
        CHECK(after[6] == before[6]);                              // p_wheel kept exactly
        CHECK(std::abs(std::sqrt(dL2) - std::sqrt(0.14)) < 2e-15); // |Delta L| = |J|: 2.2e-16
    }
    // the Hamiltonian form's momenta would need h in the action's kinematics: refused, located
    const scratch_file scene("gyrostat_kick_hamiltonian.yaml",
                             model + "form: hamiltonian\nswitch_chart: false\n" + rest);
    const run_result r =
        run_rotgen("simulate '" + scene.path + "' -o '" + scratch("gyrostat_kick_h.csv") + "'");
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: " + scene.path +
                       ":13:42: event 'kick': an action on a model with wheels needs free wheels "
                       "and the lagrangian or body form, not hamiltonian\n");
}
