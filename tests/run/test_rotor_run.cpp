// Linear rotors run (issue 14, the chapter's Example 5.4): the dumbbell hung from one end is a
// spherical pendulum in the rotor form y = (phi, theta, phi_dot, theta_dot), theta from the upward
// vertical. Checked against independent truth: p_phi and the energy are conserved; the period of
// small swings is 2 pi sqrt(I / (M g d)) (I about the pivot, d its distance from the centre of
// mass), and of a planar swing of amplitude a, through the pole of the angles (theta = pi, where
// the run changes chart), 4 sqrt(I / (M g d)) K(sin(a / 2)) with K the complete elliptic integral
// of the first kind (the exact pendulum).
#include "error_sites.hpp"
#include "support.hpp"

#include <boost/math/special_functions/ellint_1.hpp>
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <tuple>

using namespace rotgen::test;

namespace {

struct run_files {
    csv_table samples, events;
    std::string summary;
};

run_files simulate(const std::string& name, const std::string& text) {
    const scratch_file scene(name + ".yaml", text);
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/" + name + ".csv";
    const std::string events = std::string(ROTGEN_BINARY_DIR) + "/" + name + ".events.csv";
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    run_files f{read_csv(csv), {}, r.out};
    if (std::filesystem::exists(events)) f.events = read_csv(events);
    std::remove(csv.c_str());
    std::remove(events.c_str());
    return f;
}

// Two point masses on a rod along the body z axis, at s1 and s2 (signed, from the pivot).
std::string pendulum(double s1, double s2, const std::string& initial, const std::string& rest) {
    return "model:\n  name: rod_pendulum\n  parameters: {m1: 1.0, m2: 2.0, g: 9.81}\n  body:\n"
           "    pivot: [0, 0, 0]\n    parts:\n"
           "      - point: {mass: m1, at: [0, 0, " +
           std::to_string(s1) + "]}\n      - point: {mass: m2, at: [0, 0, " + std::to_string(s2) +
           "]}\n  gravity: {g: g}\ninitial: " + initial +
           "\nintegrator: {method: dop853, rtol: 1e-12, atol: 1e-14}\n" + rest;
}

// The times between successive rising zeros of Lx (the planar swing's turning points on one side).
std::vector<double> periods(const csv_table& events) {
    std::vector<double> p;
    for (std::size_t i = 1; i < events.rows.size(); ++i)
        p.push_back(events.rows[i][1] - events.rows[i - 1][1]);
    return p;
}

} // namespace

TEST_CASE("rotor: the shipped dumbbell pendulum conserves p_phi and the energy", "[run][rotor]") {
    const std::string scene =
        std::string(ROTGEN_SOURCE_DIR) + "/models/scenes/dumbbell_pendulum.yaml";
    const run_files f = simulate("rotor_shipped", read_file(scene));
    const auto e = f.samples.values("energy"), p = f.samples.values("p_phi"),
               lz = f.samples.values("Lz");
    double de = 0, dp = 0, dl = 0;
    for (std::size_t i = 0; i < e.size(); ++i) {
        de = std::max(de, std::abs(e[i] - e[0]) / std::abs(e[0]));
        dp = std::max(dp, std::abs(p[i] - p[0]) / std::abs(p[0]));
        dl = std::max(dl, std::abs(lz[i] - p[i]) / std::abs(p[0])); // L_z = p_phi (phi about z)
    }
    // measured 2.5e-11 (energy), 6.2e-10 (p_phi), 3.8e-16 (Lz - p_phi)
    CHECK(de < 3e-10);
    CHECK(dp < 6e-9);
    CHECK(dl < 4e-15);
    // the start: E = 1/2 I sin^2 theta phi_dot^2 + M g d cos theta, I = m2 l^2, M d = m2 l
    const double l = 0.3, I = 2 * l * l, mgd = 9.81 * 2 * l, th = M_PI - 0.4;
    CHECK(e[0] == Approx(0.5 * I * std::sin(th) * std::sin(th) * 0.49 + mgd * std::cos(th))
                      .epsilon(2e-15)); // measured 1.7e-16
}

TEST_CASE("rotor: small swings have the period 2 pi sqrt(I / (M g d))", "[run][rotor]") {
    // the pivot at particle 1 (hung from one end), and between the masses nearer particle 1
    const auto [s1, s2] = GENERATE(table<double, double>({{0.0, -0.3}, {0.1, -0.2}}));
    INFO("s1 = " << s1 << ", s2 = " << s2);
    // I about the pivot; M d = |sum m s|, the line pointing from the pivot to the centre of mass
    const double I = 1 * s1 * s1 + 2 * s2 * s2, mgd = 9.81 * std::abs(1 * s1 + 2 * s2);
    const double small = 2 * M_PI * std::sqrt(I / mgd), a = 0.002;
    const run_files f = simulate(
        "rotor_small",
        pendulum(
            s1, s2, "{phi: 0.3, theta: pi - 0.002, phi_dot: 0, theta_dot: 0}",
            "time: {end: " + std::to_string(3.2 * small) +
                ", samples: 11}\nrecord: [theta, Lx, Ly]\n"
                "events: [{name: turn, when: Lx*cos(0.3) + Ly*sin(0.3), direction: rising}]\n"));
    const auto p = periods(f.events);
    REQUIRE(p.size() >= 2);
    // the amplitude's correction to the period is a^2/16 = 2.5e-7; measured 2.5e-7 relative
    for (double t : p)
        CHECK(std::abs(t - small) / small < 1e-6);
    CHECK(std::abs(p[0] / (small * (1 + a * a / 16)) - 1) < 4e-12); // measured 3.9e-13, 4.2e-13
}

TEST_CASE("rotor: a planar swing through the pole keeps the exact pendulum's period",
          "[run][rotor]") {
    // amplitude a about the bottom; theta passes pi, the pole of the angles, twice a period
    // measured: the periods 5.3e-14 and 6.3e-13 relative, the energy 1.9e-12 and 1.2e-11
    const auto [a, period_bound, energy_bound] =
        GENERATE(table<double, double, double>({{0.4, 5e-13, 2e-11}, {2.5, 6e-12, 1.2e-10}}));
    INFO("amplitude " << a);
    const double l = 0.3, I = 2 * l * l, mgd = 9.81 * 2 * l;
    const double exact = 4 * std::sqrt(I / mgd) * boost::math::ellint_1(std::sin(a / 2));
    const run_files f = simulate(
        "rotor_planar",
        pendulum(0.0, -l,
                 "{phi: 0, theta: pi - " + std::to_string(a) + ", phi_dot: 0, theta_dot: 0}",
                 "time: {end: " + std::to_string(3.5 * exact) +
                     ", samples: 351}\nrecord: [theta, energy, p_phi, Lx]\n"
                     "events: [{name: turn, when: Lx, direction: rising}]\n"));
    CHECK(f.summary.find("switched to the rotor_x form") != std::string::npos);
    const auto p = periods(f.events);
    REQUIRE(p.size() >= 2);
    for (double t : p)
        CHECK(std::abs(t - exact) / exact < period_bound);
    const auto e = f.samples.values("energy"), pphi = f.samples.values("p_phi");
    for (std::size_t i = 0; i < e.size(); ++i) {
        CHECK(std::abs(e[i] - e[0]) < energy_bound * std::abs(e[0]));
        CHECK(std::abs(pphi[i]) < 4e-15); // measured 3.6e-16
    }
}

TEST_CASE("rotor: a start at the pole runs in the second chart", "[run][rotor]") {
    // theta = pi exactly (hanging), pushed sideways: phi is undefined there, chart 2 is not
    const run_files f =
        simulate("rotor_pole_start",
                 pendulum(0.0, -0.3, "{phi: 0, theta: pi, phi_dot: 0, theta_dot: 1}",
                          "time: {end: 2, samples: 201}\nrecord: [theta, energy, Lx, Ly, Lz]\n"));
    CHECK(f.summary.find("started in the rotor_x form") != std::string::npos);
    const auto e = f.samples.values("energy");
    const double I = 2 * 0.09, e0 = 0.5 * I - 9.81 * 2 * 0.3;
    for (double v : e)
        CHECK(std::abs(v - e0) < 1e-12 * std::abs(e0)); // measured 8.1e-14 relative
    // L = I n x n_dot: at t = 0, n = -e_z and n_dot = theta_dot dn/dtheta = (0, 1, 0), so
    // L = I (-e_z) x e_y = I e_x
    CHECK(f.samples.rows[0][f.samples.column("Lx")] == Approx(I).epsilon(1e-15)); // measured 0
}

TEST_CASE("rotor: what a rotor does not have is refused in one line, exit 2, nothing written",
          "[run][rotor][errors]") {
    const std::string model = "model: {name: r, inertia: [0, 1, 1], gravity: {mass: 1, g: 9.81, "
                              "com: [1, 0, 0]}}\n";
    const std::string good = "initial: {phi: 0, theta: 1, phi_dot: 0, theta_dot: 0}\n";
    using row = std::tuple<std::string, std::string, std::string>;
    const auto [name, text, line] = GENERATE_COPY(table<std::string, std::string, std::string>({
        row{"psi in initial",
            model +
                "initial: {phi: 0, theta: 1, psi: 0, phi_dot: 0, theta_dot: 0}\ntime: {end: 1}\n",
            "2:29: a linear rotor's initial state is phi, theta, phi_dot, theta_dot (the "
            "direction of its line and its rates); 'psi' is not part of it"},
        row{"initial incomplete", model + "initial: {phi: 0, theta: 1}\ntime: {end: 1}\n",
            "2:1: the initial state is incomplete: missing phi_dot, theta_dot (a rotor's state is "
            "phi, theta, phi_dot, theta_dot; nothing defaults to 0)"},
        row{"psi recorded", model + good + "time: {end: 1}\nrecord: [theta, psi]\n",
            "4:17: cannot record 'psi' for a linear rotor: psi, the turn about the line, is not a "
            "coordinate of a rotor (it moves no mass)"},
        row{"omega recorded", model + good + "time: {end: 1}\nrecord: [omega1]\n",
            "4:10: cannot record 'omega1' for a linear rotor: a linear rotor has no body axes "
            "beyond its line (its angular velocity across the line is L / I, recorded as Lx, Ly, "
            "Lz)"},
        row{"another form", model + "form: body\n" + good + "time: {end: 1}\n",
            "2:7: model 'r' is a linear rotor (Example 5.4): its form is 'rotor' (two angles phi, "
            "theta), not body"},
        row{"potential in psi",
            "model: {name: r, inertia: [0, 1, 1], potential: cos(psi)}\n" + good +
                "time: {end: 1}\n",
            "1:49: model 'r' is a linear rotor (Example 5.4): its potential may depend on phi and "
            "theta only (the direction of its line); psi, the turn about the line, is not a "
            "coordinate of a rotor"},
        row{"torque",
            "model: {name: r, inertia: [0, 1, 1], torque: [0, 0, omega1]}\n" + good +
                "time: {end: 1}\n",
            "1:46: model 'r' is a linear rotor (Example 5.4): rotgen models no 'torque' on a "
            "rotor (its generalised forces act on phi and theta only); leave it out, or write "
            "the force as a potential in phi and theta"},
        row{"centre of mass off the line",
            "model: {name: r, inertia: [0, 1, 1], gravity: {mass: 1, g: 9.81, com: [0, 0, 1]}}\n" +
                good + "time: {end: 1}\n",
            "1:47: model 'r' is a linear rotor (Example 5.4): the centre of mass (gravity 'com') "
            "must lie on its line (the axis of its zero moment)"},
        row{"a split method",
            model + good + "time: {end: 1}\nintegrator: {method: split4, step: 0.01}\n",
            "4:13: integrator split4 steps a three-axis body (Euler's equations); a linear rotor "
            "has two angles: use dop853, dopri5, rk4, implicit_midpoint, rosenbrock or taylor"},
    }));
    INFO(name);
    const scratch_file scene("rotor_bad.yaml", text);
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/rotor_bad.csv";
    check_error_line(run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'"),
                     scene.path + ":" + line);
    CHECK(!std::filesystem::exists(csv));
}

TEST_CASE("scene parameters that make the body unphysical are refused at the parameters key",
          "[run][rotor][errors]") {
    // the model's physical checks run again at the scene's values (scene.cpp), for a rotor from
    // parts as for a top given by its moments
    const std::string pendulum_model =
        "model:\n  name: p\n  parameters: {m1: 1, m2: 2}\n  body:\n    pivot: [0, 0, 0]\n"
        "    parts:\n      - point: {mass: m1, at: [0, 0, 0]}\n"
        "      - point: {mass: m2, at: [0, 0, -1]}\n  gravity: {g: 9.81}\n";
    const std::string rotor_start = "initial: {phi: 0, theta: 1, phi_dot: 0, theta_dot: 0}\n"
                                    "time: {end: 1}\n";
    const std::string top_start =
        "initial: {phi: 0, theta: 1, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\n"
        "time: {end: 1}\n";
    const std::string top = "model: {name: t, parameters: {a: 1}, inertia: [a, 1, 1]}\n";
    using row = std::tuple<std::string, std::string, std::string>;
    const auto [name, text, line] = GENERATE_COPY(table<std::string, std::string, std::string>({
        row{"a negative mass of a part", pendulum_model + "parameters: {m2: -2}\n" + rotor_start,
            "10:13: with these parameter values the model (@) is not valid: point mass must be "
            "positive (with these values), got -2"},
        row{"a negative moment", top + "parameters: {a: -1}\n" + top_start,
            "2:13: with these parameter values the model (@) is not valid: inertia is not "
            "physical: a principal moment is negative (-1, 1, 1)"},
        row{"the triangle inequality", top + "parameters: {a: 3}\n" + top_start,
            "2:13: with these parameter values the model (@) is not valid: inertia is not "
            "physical: principal moments (1, 1, 3) break the triangle inequality (each at most "
            "the sum of the other two): 1 + 1 < 3"},
    }));
    INFO(name);
    const scratch_file scene("unphysical_scene.yaml", text);
    std::string expected = scene.path + ":" + line;
    expected.replace(expected.find('@'), 1, scene.path);
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/unphysical_scene.csv";
    check_error_line(run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'"), expected);
    CHECK(!std::filesystem::exists(csv));
}

TEST_CASE("rotor: a sweep runs a rotor's members and refuses psi as a key", "[run][rotor][sweep]") {
    const std::string scene =
        std::string(ROTGEN_SOURCE_DIR) + "/models/scenes/dumbbell_pendulum.yaml";
    const scratch_dir out("rotor_sweep");
    check_error_line(run_rotgen("sweep '" + scene + "' -o '" + out.path.string() +
                                "' --vary initial.psi=0:1:2 -q"),
                     "rotgen sweep --vary initial.psi=0:1:2: sweep key 'initial.psi': a linear "
                     "rotor's state is phi, theta, phi_dot, theta_dot");
    CHECK(!std::filesystem::exists(out.path));
    // two members: the energy E = 1/2 I sin^2 theta phi_dot^2 + M g d cos theta of each start
    const run_result r = run_rotgen("sweep '" + scene + "' -o '" + out.path.string() +
                                    "' --vary initial.theta=2.5:3.0:2 -q");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const csv_table t = read_csv((out.path / "summary.csv").string());
    REQUIRE(t.rows.size() == 2);
    const double I = 2 * 0.09, mgd = 9.81 * 2 * 0.3;
    for (const auto& row : t.rows) {
        const double th = row[t.column("initial.theta")];
        const double e0 = 0.5 * I * std::sin(th) * std::sin(th) * 0.49 + mgd * std::cos(th);
        // the final energy against the start's: measured 7.4e-11 and 1.7e-12 relative; the drift
        // 9.1e-11 and 5.6e-12
        CHECK(std::abs(row[t.column("final.energy")] - e0) < 7e-10 * std::abs(e0));
        CHECK(row[t.column("drift.energy")] < 9e-10 * std::abs(e0));
    }
}
