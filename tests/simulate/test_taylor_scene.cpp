// `integrator: {method: taylor}` in a scene: the run engine compiles the Taylor coefficients with
// the kernels and integrates with the Taylor method (runtime/steppers/taylor.hpp).
#include "error_sites.hpp"
#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace rotgen;
using namespace rotgen::test;

TEST_CASE("a taylor scene agrees with dop853 and keeps the heavy top's invariants", "[simulate]") {
    const auto scene = [](const std::string& name, const std::string& integrator) {
        return scratch_file(
            name,
            "model: " + model_path("heavy_top") +
                "\ninitial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}\n"
                "time: {end: 5, samples: 501}\n"
                "integrator: " +
                integrator + "\nrecord: [theta, energy, p_phi, p_psi]\n");
    };
    const scratch_file taylor =
        scene("taylor_scene.yaml", "{method: taylor, rtol: 1e-13, atol: 1e-13}");
    const scratch_file dop = scene("dop_scene.yaml", "{method: dop853, rtol: 1e-13, atol: 1e-13}");
    for (const auto* s : {&taylor, &dop}) {
        const run_result r = run_rotgen("simulate '" + s->path + "' -o '" + s->path + ".csv'");
        INFO(r.out << r.err);
        REQUIRE(r.status == 0);
    }
    const csv_table a = read_csv(taylor.path + ".csv"), b = read_csv(dop.path + ".csv");
    std::remove((taylor.path + ".csv").c_str());
    std::remove((dop.path + ".csv").c_str());
    REQUIRE(a.rows.size() == 501);
    double diff = 0, drift = 0, drift_phi = 0, drift_psi = 0;
    for (std::size_t i = 0; i < a.rows.size(); ++i) {
        diff = std::max(diff, std::abs(a.values("theta")[i] - b.values("theta")[i]));
        drift = std::max(drift, std::abs(a.values("energy")[i] - a.values("energy")[0]));
        drift_phi = std::max(drift_phi, std::abs(a.values("p_phi")[i] - a.values("p_phi")[0]));
        drift_psi = std::max(drift_psi, std::abs(a.values("p_psi")[i] - a.values("p_psi")[0]));
    }
    // p_psi = I3 (psi_dot + phi_dot cos theta) = 15 and p_phi = p_psi cos(0.5) = 13.16 (5.74),
    // both conserved (phi and psi are cyclic): observed drifts 3.9e-14 and 1.2e-14
    CHECK(a.values("p_psi")[0] == Approx(0.5 * 30).epsilon(1e-15));
    CHECK(a.values("p_phi")[0] == Approx(0.5 * 30 * std::cos(0.5)).epsilon(1e-15));
    CHECK(drift_phi < 4e-13);
    CHECK(drift_psi < 1.5e-13);
    // observed: theta within 5.9e-14 of dop853's; energy drift 3.1e-13 of E = 225.9 (1.4e-15)
    CHECK(diff < 5e-13);
    CHECK(drift < 1e-14 * a.values("energy")[0]);
}

TEST_CASE(
    "a model whose rates the Taylor recurrences do not cover is refused where it is asked for",
    "[simulate][errors]") {
    const scratch_file model("taylor_tan.yaml",
                             "name: tan_top\ninertia: [1, 1, 2]\npotential: 0.1*tan(theta)\n");
    const scratch_file scene(
        "taylor_tan_scene.yaml",
        "model: taylor_tan.yaml\n"
        "initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 3}\n"
        "time: {end: 1}\nintegrator: {method: taylor}\n");
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/taylor_tan.csv";
    std::remove(csv.c_str());
    check_error_line(
        run_rotgen("simulate taylor_tan_scene.yaml -o '" + csv + "'", ROTGEN_BINARY_DIR),
        "taylor_tan_scene.yaml:4:13: integrator taylor cannot run model 'tan_top': "
        "the Taylor recurrences do not cover 'tan' (in the rates); use dop853, "
        "dopri5, rk4, implicit_midpoint or rosenbrock");
    CHECK(read_file(csv).empty());
    const scratch_dir out("taylor_tan_out");
    check_error_line(
        run_rotgen("emit taylor_tan.yaml --outputs rhs,taylor -o '" + out.path.string() + "'",
                   ROTGEN_BINARY_DIR),
        "taylor_tan.yaml:1:1: model 'tan_top': the Taylor recurrences do not cover "
        "'tan' (in the rates); leave taylor out of --outputs");
    CHECK(!std::filesystem::exists(out.path));
}
