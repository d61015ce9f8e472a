// Damping in body axes, damping: {body: [c1, c2, c3]}: the torque -c_i omega_i (and torques
// written in omega1..3), in the body form directly and in the Euler-angle forms as Q = J^T tau
// (5.30). Checked against the exact decay of a free symmetric top's spin and against the energy
// balance dE/dt = -sum c_i omega_i^2.
#include "support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <tuple>

using namespace rotgen::test;

namespace {

csv_table simulate(const std::string& name, const std::string& text) {
    const scratch_file scene(name + ".yaml", text);
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/" + name + ".csv";
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    csv_table t = read_csv(csv);
    std::remove(csv.c_str());
    return t;
}

std::string scene(const std::string& model, const std::string& form, const std::string& rest) {
    return "model: " + model + "\nform: " + form +
           "\ninitial: {phi: 0.2, theta: 1.1, psi: 0.7, omega1: 0.6, omega2: -0.4, omega3: 2}\n"
           "integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}\n" +
           rest;
}

} // namespace

TEST_CASE("body damping c3 of a free symmetric top: omega3 decays as exp(-c3 t / I3) exactly",
          "[run][damping]") {
    // I1 = I2: I3 omega3_dot = (I1 - I2) omega1 omega2 - c3 omega3 = -c3 omega3, and
    // |omega_perp| is constant (I1 d|w_perp|^2/dt / 2 = (I2 - I3 + I3 - I1) w1 w2 w3 = 0).
    const std::string form = GENERATE(as<std::string>{}, "lagrangian", "hamiltonian", "body");
    INFO(form);
    const std::string model = "{name: damped_symmetric, parameters: {c3: 0.3}, inertia: [2, 2, "
                              "0.5], damping: {body: [0, 0, c3]}}";
    const csv_table t =
        simulate("body_damping_" + form, scene(model, form,
                                               "time: {end: 5, samples: 51}\nswitch_chart: false\n"
                                               "record: [omega1, omega2, omega3]\n"));
    double worst = 0, perp = 0;
    for (const auto& r : t.rows) {
        const double exact = 2 * std::exp(-0.3 * r[0] / 0.5);
        worst = std::max(worst, std::abs(r[3] - exact) / exact);
        perp = std::max(perp, std::abs(std::hypot(r[1], r[2]) - std::hypot(0.6, 0.4)));
    }
    // measured 3.1e-12 (lagrangian), 1.2e-13 (hamiltonian), 5.9e-13 (body); |omega_perp|:
    // 2.1e-13, 2.6e-12, 7.2e-13
    CHECK(worst < 2e-11);
    CHECK(perp < 2e-11);
}

TEST_CASE("body damping: E(t) - E(0) is minus the dissipated work, the integral of sum c_i w_i^2",
          "[run][damping]") {
    const std::string form = GENERATE(as<std::string>{}, "lagrangian", "body");
    INFO(form);
    const std::string model =
        "{name: damped_asymmetric, parameters: {c1: 0.2, c2: 0.1, c3: 0.05}, inertia: [1, 2, 3], "
        "damping: {body: [c1, c2, c3]}}";
    const csv_table t = simulate("body_damping_energy_" + form,
                                 scene(model, form,
                                       "time: {end: 4, samples: 801}\nswitch_chart: false\n"
                                       "record: [omega1, omega2, omega3, energy]\n"));
    // Simpson's rule over pairs of sample intervals (h = 0.005, error ~ h^4 P'''' / 180)
    const auto power = [&](std::size_t k) {
        const auto& r = t.rows[k];
        return 0.2 * r[1] * r[1] + 0.1 * r[2] * r[2] + 0.05 * r[3] * r[3];
    };
    const double h = 4.0 / 800;
    double work = 0, worst = 0;
    for (std::size_t k = 2; k < t.rows.size(); k += 2) {
        work += h / 3 * (power(k - 2) + 4 * power(k - 1) + power(k));
        worst = std::max(worst, std::abs(t.rows[k][4] - t.rows[0][4] + work));
    }
    CHECK(t.rows.back()[4] < 0.9 * t.rows[0][4]); // it loses 15% of its energy: 6.34 -> 5.39
    // measured 1.7e-11 (lagrangian), 1.1e-11 (body): Simpson's error at h = 0.005
    CHECK(worst < 1e-10);
}

TEST_CASE("a torque written in omega1..3 is the same as the body damping it spells out",
          "[run][damping]") {
    const std::string a = "{name: by_damping, inertia: [1, 2, 3], damping: {body: [0.2, 0, 0.1]}}";
    const std::string b = "{name: by_torque, inertia: [1, 2, 3], torque: [\"-0.2*omega1\", \"0\", "
                          "\"-omega3/10\"]}";
    const std::string rest = "time: {end: 3, samples: 31}\nrecord: [theta, omega1, omega3]\n";
    const csv_table ta = simulate("torque_a", scene(a, "hamiltonian", rest));
    const csv_table tb = simulate("torque_b", scene(b, "hamiltonian", rest));
    REQUIRE(ta.rows.size() == tb.rows.size());
    for (std::size_t k = 0; k < ta.rows.size(); ++k)
        for (std::size_t c = 1; c < 4; ++c)
            CHECK(tb.rows[k][c] == Approx(ta.rows[k][c]).margin(1e-14));
}

TEST_CASE("bad body damping is reported at its place", "[run][damping][errors]") {
    using row = std::tuple<std::string, std::string>;
    const auto [damping, expected] = GENERATE(table<std::string, std::string>({
        row{"{body: [1, 2]}", "3:17: damping 'body' must be a list of three coefficients [c1, "
                              "c2, c3] (the torque -c_i omega_i about body axis i)"},
        row{"{axes: [1, 2, 3]}", "3:11: unknown field 'axes' in damping"},
        row{"{body: [1, 2, omega3]}", "3:24: unknown symbol 'omega3' in damping"},
    }));
    const scratch_file model("body_damping_bad.yaml",
                             "name: top\ninertia: [1, 2, 3]\ndamping: " + damping + "\n");
    const run_result r = run_rotgen("inspect '" + model.path + "'");
    CHECK(r.status == 2);
    CHECK(r.err.rfind("rotgen: error: " + model.path + ":" + expected, 0) == 0);
}
