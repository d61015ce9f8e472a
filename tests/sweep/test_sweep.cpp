// rotgen sweep: the members a plan gives (grid, zip, random with its seed), a member's row against
// `rotgen simulate` of the same scene with its values written in, a failing member among others.
#include "support.hpp"

#include "run/engine.hpp"
#include "run/prepared.hpp"
#include "scene/scene.hpp"
#include "support/timings.hpp"
#include "sweep/members.hpp"

#include <catch2/catch.hpp>

#include <functional>
#include <sstream>

using namespace rotgen;
using namespace rotgen::test;

namespace {

std::string scratch(const std::string& name) {
    return std::string(ROTGEN_BINARY_DIR) + "/" + name;
}

std::string heavy_top_scene(const std::string& initial, const std::string& rest) {
    return "model: " + model_path("heavy_top") + "\ninitial: " + initial +
           "\ntime: {end: 2, samples: 201}\n"
           "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}\n"
           "record: [theta, phi, energy, p_phi]\n" +
           rest;
}

std::vector<std::vector<double>> rows_of(const std::string& sweep_block,
                                         const std::vector<std::string>& cli = {}) {
    const std::string text = heavy_top_scene(
        "{phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}", sweep_block);
    // one file per text: the test cases run as parallel processes under ctest -j
    const scratch_file f("sweep_plan_" + std::to_string(std::hash<std::string>{}(text)) + ".yaml",
                         text);
    return member_rows(read_sweep_plan(load_scene(f.path), cli));
}

// The fields of one CSV line (no quoted commas in the lines compared here).
std::vector<std::string> fields(const std::string& line) {
    std::vector<std::string> out;
    std::istringstream in(line);
    std::string cell;
    while (std::getline(in, cell, ','))
        out.push_back(cell);
    return out;
}

} // namespace

TEST_CASE("sweep: a grid counts like nested loops, the last key fastest", "[sweep]") {
    const auto rows = rows_of("sweep:\n  vary:\n    initial.theta: {from: 0.2, to: 0.6, count: 3}\n"
                              "    parameters.h: {values: [0.1, 0.3]}\n");
    const std::vector<std::vector<double>> expected{{0.2, 0.1}, {0.2, 0.3}, {0.4, 0.1},
                                                    {0.4, 0.3}, {0.6, 0.1}, {0.6, 0.3}};
    REQUIRE(rows.size() == expected.size());
    for (std::size_t m = 0; m < rows.size(); ++m) {
        CHECK(rows[m][0] == Approx(expected[m][0]).epsilon(1e-15));
        CHECK(rows[m][1] == expected[m][1]);
    }
    CHECK(rows.back()[0] == 0.6); // the last value of a range is `to` exactly
}

TEST_CASE("sweep: zip pairs the i-th values, and --vary adds a key or replaces one", "[sweep]") {
    const auto zip =
        rows_of("sweep:\n  mode: zip\n  vary:\n    initial.theta: {values: [0.1, 0.2]}\n"
                "    initial.psi_dot: {from: 10, to: 20, count: 2}\n");
    CHECK(zip == std::vector<std::vector<double>>{{0.1, 10}, {0.2, 20}});
    const auto cli = rows_of("sweep:\n  vary:\n    initial.theta: {values: [0.1, 0.2]}\n",
                             {"initial.theta=0.3,0.4,0.5", "parameters.M=1:2:2"});
    CHECK(cli == std::vector<std::vector<double>>{
                     {0.3, 1}, {0.3, 2}, {0.4, 1}, {0.4, 2}, {0.5, 1}, {0.5, 2}});
}

TEST_CASE("sweep: initial.phi varies beside other keys", "[sweep]") {
    // Each key was once checked against keys not yet resolved, whose slot defaulted to phi's: a
    // plan whose first key was initial.phi was refused as "setting the same value" as the next.
    const auto rows =
        rows_of("sweep:\n  mode: zip\n  vary:\n    initial.phi: {values: [0.1, 0.2]}\n"
                "    initial.psi_dot: {values: [10, 20]}\n");
    CHECK(rows == std::vector<std::vector<double>>{{0.1, 10}, {0.2, 20}});
}

TEST_CASE("sweep: random members come from mt19937_64(seed), 53 bits each", "[sweep]") {
    // The C++ standard fixes mt19937_64: the 10000th output of a default-seeded (5489) engine is
    // 9981545732273789042 ([rand.predef]). With one key over [0, 1) member 9999 is that output's
    // top 53 bits times 2^-53.
    const auto rows = rows_of("sweep:\n  mode: random\n  members: 10000\n  seed: 5489\n"
                              "  vary:\n    parameters.h: {from: 0, to: 1}\n");
    REQUIRE(rows.size() == 10000);
    CHECK(rows[9999][0] == double(9981545732273789042ULL >> 11) * 0x1.0p-53);
    const auto again = rows_of("sweep:\n  mode: random\n  members: 10000\n  seed: 5489\n"
                               "  vary:\n    parameters.h: {from: 0, to: 1}\n");
    CHECK(again == rows);
    const auto other = rows_of("sweep:\n  mode: random\n  members: 3\n  seed: 42\n"
                               "  vary:\n    initial.theta: {from: 0.5, to: 1}\n"
                               "    parameters.h: {from: 0.1, to: 0.2}\n");
    REQUIRE(other.size() == 3);
    for (const auto& r : other) {
        CHECK((r[0] >= 0.5 && r[0] < 1));
        CHECK((r[1] >= 0.1 && r[1] < 0.2));
    }
    CHECK(other[0][0] != other[1][0]);
}

TEST_CASE("sweep: a member's row is what simulate gives with the member's values written in",
          "[sweep]") {
    const scratch_file scene(
        "sweep_member.yaml",
        heavy_top_scene("{phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}",
                        "sweep:\n  vary:\n    initial.theta: {values: [0.3, 0.7]}\n"
                        "    parameters.h: {values: [0.1, 0.25]}\n"));
    const std::string dir = scratch("sweep_member_out");
    const test::run_result r = run_rotgen("sweep '" + scene.path + "' -o '" + dir + "' -q");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto summary = text_lines(read_file(dir + "/summary.csv"));
    REQUIRE(summary.size() == 5);
    CHECK(summary[0] ==
          "member,initial.theta,parameters.h,final.t,final.theta,final.phi,"
          "final.energy,final.p_phi,drift.energy,drift.p_phi,drift.p_psi,steps,rhs_evals,"
          "status");
    // member 3: theta 0.7, h 0.25
    const scratch_file single(
        "sweep_member_single.yaml",
        heavy_top_scene("{phi: 0, theta: 0.7, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}",
                        "parameters: {h: 0.25}\n"));
    const test::run_result s =
        run_rotgen("simulate '" + single.path + "' -o '" + scratch("sweep_member.csv") + "'");
    REQUIRE(s.status == 0);
    const auto sim = text_lines(read_file(scratch("sweep_member.csv")));
    const std::vector<std::string> row = fields(summary[4]);
    CHECK(std::vector<std::string>(row.begin(), row.begin() + 3) ==
          std::vector<std::string>{"3", "0.7", "0.25"});
    // final.t .. final.p_phi: the simulated last sample, digit for digit
    CHECK(std::vector<std::string>(row.begin() + 3, row.begin() + 8) == fields(sim.back()));
    CHECK(row.back() == "ok");
    // steps and RHS evaluations as simulate counts them ("430 accepted, ...; 6710 RHS")
    CHECK(s.out.find("  steps   " + row[11] + " accepted") != std::string::npos);
    CHECK(s.out.find("; " + row[12] + " RHS and") != std::string::npos);
}

TEST_CASE("sweep: a failing member is reported with its reason while the others finish",
          "[sweep]") {
    // theta = 0 with switch_chart: false cannot start in the Euler-angle chart; a fast spin
    // needs more steps than max_steps allows. The others run to the end.
    const scratch_file scene(
        "sweep_failing.yaml",
        "model: " + model_path("heavy_top") +
            "\ninitial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}\ntime: "
            "{end: 2, samples: 21}\n"
            "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12, max_steps: 400}\n"
            "switch_chart: false\nrecord: [theta]\n"
            "sweep:\n  mode: zip\n  vary:\n    initial.theta: {values: [0.5, 0, 0.6, 0.5]}\n"
            "    initial.psi_dot: {values: [30, 30, 30, 3000]}\n");
    const std::string dir = scratch("sweep_failing_out");
    const test::run_result r = run_rotgen("sweep '" + scene.path + "' -o '" + dir + "' -q");
    INFO(r.err);
    CHECK(r.status == 3);
    const auto summary = text_lines(read_file(dir + "/summary.csv"));
    REQUIRE(summary.size() == 5);
    CHECK(fields(summary[1]).back() == "ok");
    CHECK(fields(summary[3]).back() == "ok");
    CHECK(fields(summary[1])[3] == "2");
    CHECK(summary[2].find("initial theta = 0 is the gimbal-lock singularity") != std::string::npos);
    CHECK(summary[4].find(",400,") != std::string::npos); // the steps taken: the bound
    // the last sample before max_steps (0.1 before issue 50's step control, 0.3 with it per step,
    // 0.2 per unit step)
    CHECK(summary[4].find(",stopped at t = 0.2: max_steps = 400 reached at t = ") !=
          std::string::npos);
    CHECK(r.err.find("member 1: ") != std::string::npos);
    CHECK(r.err.find("member 3: stopped at t = ") != std::string::npos);
}

TEST_CASE("sweep: -j 1 and -j 2 write the same files, byte for byte", "[sweep]") {
    // Members of different costs (spin 5 .. 200) and one that fails, so that two threads finish
    // them in another order than one thread does.
    const scratch_file scene(
        "sweep_threads.yaml",
        heavy_top_scene("{phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}",
                        "sweep:\n  vary:\n    initial.psi_dot: {from: 5, to: 200, count: 12}\n"
                        "    initial.theta: {values: [0.3, 0, 1.2]}\nswitch_chart: false\n"));
    std::string files[2], h5[2];
    for (int j = 1; j <= 2; ++j) {
        const std::string dir = scratch("sweep_threads_" + std::to_string(j));
        const test::run_result r = run_rotgen("sweep '" + scene.path + "' -o '" + dir +
                                              "' -q --trajectories -j " + std::to_string(j));
        INFO(r.err);
        CHECK(r.status == 3); // the theta = 0 members
        files[j - 1] = read_file(dir + "/summary.csv");
        h5[j - 1] = read_file(dir + "/trajectories.h5");
    }
    CHECK(h5[0].size() > 36 * 201 * 5 * 8); // members x samples x columns x 8 bytes
    CHECK(h5[0] == h5[1]);
    CHECK(text_lines(files[0]).size() == 37);
    CHECK(files[0] == files[1]);
}

TEST_CASE("sweep: event.<name> is the time of the event's first occurrence, empty if none",
          "[sweep]") {
    // The heavy top spun at 10 nods between theta0 and a turning point: theta0 = 0.8 turns at
    // theta 0.861 (twice in t = 0..2) and passes 0.85 on the way; theta0 = 0.3 never gets there.
    const std::string events = "events:\n  - {name: turn, when: theta_dot, direction: falling}\n"
                               "  - {name: deep, when: theta - 0.85, direction: rising}\n";
    const auto scene_at = [&](const std::string& theta, const std::string& rest) {
        return heavy_top_scene("{phi: 0, theta: " + theta +
                                   ", psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 10}",
                               events + rest);
    };
    const scratch_file scene("sweep_events.yaml",
                             scene_at("0.5", "sweep:\n  vary:\n    initial.theta: "
                                             "{values: [0.3, 0.8]}\n"));
    std::string summaries[2];
    for (int j = 1; j <= 2; ++j) {
        const std::string dir = scratch("sweep_events_" + std::to_string(j));
        const test::run_result r =
            run_rotgen("sweep '" + scene.path + "' -o '" + dir + "' -q -j " + std::to_string(j));
        INFO(r.err);
        REQUIRE(r.status == 0);
        summaries[j - 1] = read_file(dir + "/summary.csv");
    }
    CHECK(summaries[0] == summaries[1]);
    const auto summary = text_lines(summaries[0]);
    REQUIRE(summary.size() == 3);
    CHECK(summary[0] == "member,initial.theta,final.t,final.theta,final.phi,final.energy,"
                        "final.p_phi,event.turn,event.deep,drift.energy,drift.p_phi,drift.p_psi,"
                        "steps,rhs_evals,status");
    for (int m = 0; m < 2; ++m) {
        const std::string theta = m == 0 ? "0.3" : "0.8";
        const scratch_file single("sweep_events_single.yaml", scene_at(theta, ""));
        const std::string csv = scratch("sweep_events_" + theta + ".csv");
        const test::run_result s = run_rotgen("simulate '" + single.path + "' -o '" + csv + "'");
        REQUIRE(s.status == 0);
        // The first row of each event in <output>.events.csv: its t, digit for digit.
        std::string first_turn, first_deep;
        std::size_t turns = 0;
        for (const auto& line :
             text_lines(read_file(scratch("sweep_events_" + theta + ".events.csv")))) {
            const auto f = fields(line);
            if (f[0] == "turn" && turns++ == 0) first_turn = f[1];
            if (f[0] == "deep" && first_deep.empty()) first_deep = f[1];
        }
        const std::vector<std::string> row = fields(summary[1 + m]);
        INFO("member " << m);
        REQUIRE(row.size() == 15);
        CHECK(row[1] == theta);
        CHECK(!first_turn.empty());
        CHECK(row[7] == first_turn);
        CHECK(row[8] == first_deep);
        CHECK(row.back() == "ok");
        if (m == 0) CHECK(first_deep.empty()); // the empty field: theta0 = 0.3 stays below 0.85
        if (m == 1) CHECK(turns == 2);         // the first of two turning points
    }
}

TEST_CASE("sweep: a member run that keeps its last row only has that row and every drift of the "
          "full run",
          "[sweep]") {
    // a sweep without --trajectories needs the last row and the invariants at every sample
    const scratch_file f("sweep_last_row.yaml",
                         heavy_top_scene("{phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, "
                                         "psi_dot: 30}",
                                         ""));
    stage_timings timings;
    const prepared_scene every(load_scene(f.path), timings);
    prepared_scene last(load_scene(f.path), timings);
    last.keep_last_row_only();
    const rotgen::run_result all = run_member(every, values_of(every.scene()), timings);
    const rotgen::run_result one = run_member(last, values_of(last.scene()), timings);
    REQUIRE(all.rows.size() == 201);
    REQUIRE(one.rows.size() == 1);
    CHECK(one.rows[0] == all.rows.back()); // the same doubles: t = 2 and the recorded columns
    REQUIRE(one.invariants.size() == all.invariants.size());
    REQUIRE(all.invariants.size() >= 2); // the energy and p_phi at least
    for (std::size_t i = 0; i < all.invariants.size(); ++i) {
        CHECK(one.invariants[i].drift == all.invariants[i].drift);
        CHECK(one.invariants[i].drift > 0); // taken over the samples, not left at 0
    }
    CHECK(one.stats.accepted == all.stats.accepted);
}
