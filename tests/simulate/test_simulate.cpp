// `rotgen simulate` end to end: derive -> emit -> compile -> integrate -> CSV, checked against the
// physics of the chapter (5.74-5.79, 5.94, 5.100) and for its handling of bad scenes.
#include "support.hpp"

#include <exact_free_top.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

using namespace rotgen::test;

namespace {

std::string scratch(const std::string& name) {
    return std::string(ROTGEN_BINARY_DIR) + "/" + name;
}

// A scene file in the build tree that names a shipped model by absolute path.
std::string scene_text(const std::string& model, const std::string& rest) {
    return "model: " + model_path(model) + "\n" + rest;
}

double max_abs_change(const std::vector<double>& v) {
    double m = 0;
    for (double x : v)
        m = std::max(m, std::abs(x - v.front()));
    return m;
}

} // namespace

TEST_CASE("heavy top: theta nods between the turning points of the effective potential",
          "[simulate]") {
    // Parameters of models/heavy_top.yaml.
    const double I1 = 1.0, I3 = 0.5, M = 1.0, g = 9.81, h = 0.1;
    const double theta0 = 0.5, spin = 30; // psi_dot; phi_dot = theta_dot = 0
    const scratch_file scene(
        "nutation_scene.yaml",
        scene_text("heavy_top",
                   "initial: {theta: 0.5, psi_dot: 30, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0}\n"
                   "time: {end: 5, samples: 5001}\n"
                   "integrator: {method: dop853, rtol: 1e-11, atol: 1e-13}\n"
                   "record: [theta, energy, p_phi, p_psi]\n"));
    const run_result r =
        run_rotgen("simulate '" + scene.path + "' -o '" + scratch("nutation.csv") + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const csv_table t = read_csv(scratch("nutation.csv"));
    REQUIRE(t.rows.size() == 5001);
    CHECK(t.header == std::vector<std::string>{"t", "theta", "energy", "p_phi", "p_psi"});

    // (5.74)-(5.76) at t = 0: p_psi = I3 psi_dot, p_phi = p_psi cos(theta); both conserved.
    const double p_psi = I3 * spin, p_phi = p_psi * std::cos(theta0);
    CHECK(t.values("p_psi").front() == Approx(p_psi).epsilon(1e-14));
    CHECK(t.values("p_phi").front() == Approx(p_phi).epsilon(1e-14));
    CHECK(max_abs_change(t.values("p_phi")) < 1e-11 * p_phi);
    CHECK(max_abs_change(t.values("p_psi")) < 1e-11 * p_psi);
    CHECK(max_abs_change(t.values("energy")) < 1e-10 * t.values("energy").front());

    // Turning points: with u = cos(theta), (5.79) gives theta_dot = 0 where
    //   f(u) = (beta - alpha u)(1 - u^2) - (b - a u)^2 = 0,
    // a = p_psi/I1, b = p_phi/I1, alpha = 2 M g h/I1, beta = 2 E'/I1, E' = E - p_psi^2/(2 I3).
    const double E = t.values("energy").front();
    const double a = p_psi / I1, b = p_phi / I1, alpha = 2 * M * g * h / I1;
    const double beta = 2 * (E - p_psi * p_psi / (2 * I3)) / I1;
    const auto f = [&](double u) {
        return (beta - alpha * u) * (1 - u * u) - (b - a * u) * (b - a * u);
    };
    // u0 = cos(theta0) is one root; the other in (-1, u0) by bisection.
    const double u0 = std::cos(theta0);
    CHECK(std::abs(f(u0)) < 1e-9);
    double lo = -1 + 1e-12, hi = u0 - 1e-9;
    REQUIRE(f(lo) * f(hi) < 0);
    for (int i = 0; i < 200; ++i) {
        const double mid = (lo + hi) / 2;
        (f(lo) * f(mid) <= 0 ? hi : lo) = mid;
    }
    const double theta_max = std::acos((lo + hi) / 2);
    const auto theta = t.values("theta");
    const double sampled_max = *std::max_element(theta.begin(), theta.end());
    const double sampled_min = *std::min_element(theta.begin(), theta.end());
    CHECK(sampled_min == Approx(theta0).margin(1e-9));
    // samples every 1e-3 resolve the maximum to ~ theta_ddot dt^2 / 8 (< 1e-6 here)
    CHECK(sampled_max == Approx(theta_max).margin(1e-6));
    CHECK(sampled_max > theta0 + 1e-3); // it does nod
}

TEST_CASE("free asymmetric top: stable about axes 1 and 3, flips about axis 2", "[simulate]") {
    for (int axis : {1, 2, 3}) {
        const std::string csv = scratch("free_axis" + std::to_string(axis) + ".csv");
        const run_result r = run_rotgen("simulate '" + std::string(ROTGEN_SOURCE_DIR) +
                                        "/models/scenes/free_top_axis" + std::to_string(axis) +
                                        ".yaml' -o '" + csv + "'");
        INFO("axis " << axis << "\n" << r.out << r.err);
        REQUIRE(r.status == 0);
        const auto w = read_csv(csv).values("omega" + std::to_string(axis));
        const double lowest = *std::min_element(w.begin(), w.end());
        if (axis == 2)
            CHECK(lowest < -0.9); // the intermediate axis: omega2 reverses (5.100)
        else
            CHECK(lowest > 0.99); // small oscillations only (5.94)
    }
}

TEST_CASE("body form and Lagrangian form agree away from theta = 0", "[simulate]") {
    std::vector<double> theta[2];
    int k = 0;
    for (const char* form : {"lagrangian", "body"}) {
        const scratch_file scene(
            "form_scene.yaml",
            scene_text("full_tensor_top",
                       std::string("form: ") + form +
                           "\ninitial: {phi: 0.2, theta: 1.1, psi: 0.4, phi_dot: 0.3, theta_dot: "
                           "-0.2, psi_dot: 6}\ntime: {end: 3, samples: 31}\n"
                           "integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}\n"
                           "record: [theta, energy]\n"));
        const run_result r =
            run_rotgen("simulate '" + scene.path + "' -o '" + scratch("form.csv") + "'");
        INFO(form << "\n" << r.out << r.err);
        REQUIRE(r.status == 0);
        theta[k++] = read_csv(scratch("form.csv")).values("theta");
    }
    REQUIRE(theta[0].size() == theta[1].size());
    for (std::size_t i = 0; i < theta[0].size(); ++i)
        CHECK(theta[1][i] == Approx(theta[0][i]).margin(1e-9));
}

TEST_CASE("gimbal lock: theta = 0 starts in the body form, or is refused when no chart is free",
          "[simulate][gimbal]") {
    const std::string common =
        "initial: {theta: 0, omega1: 0.1, omega2: 0.2, omega3: 1, phi: 0, psi: 0}\n"
        "time: {end: 10, samples: 11}\nrecord: [omega1, theta, phi_dot, energy]\n";
    // The damped model's damping acts on Euler-angle rates: its body form is singular too.
    const scratch_file damped("lock_damped.yaml",
                              scene_text("damped_driven_top", "form: hamiltonian\n" + common));
    const run_result bad = run_rotgen("simulate '" + damped.path + "'");
    CHECK(bad.status == 2);
    CHECK(bad.err.find("lock_damped.yaml:3:10: initial theta = 0 is the gimbal-lock singularity") !=
          std::string::npos);
    const scratch_file free_top("lock_free.yaml",
                                scene_text("free_asymmetric_top", "form: hamiltonian\n" + common));
    const run_result good =
        run_rotgen("simulate '" + free_top.path + "' -o '" + scratch("lock.csv") + "'");
    INFO(good.out << good.err);
    CHECK(good.status == 0);
    CHECK(good.out.find("chart   started in the body form (initial |sin theta| = 0 < 0.1)") !=
          std::string::npos);
    // phi_dot is undefined at theta = 0: written as inf, and said so in the summary.
    CHECK(good.out.find("recorded values are not finite") != std::string::npos);
    const csv_table t = read_csv(scratch("lock.csv"));
    CHECK(t.values("theta").front() == Approx(0).margin(1e-12));
    CHECK(t.values("theta").back() > 0.01); // it moves off the singular point
    CHECK(std::isfinite(t.values("phi_dot").back()));
}

TEST_CASE("a free top tumbling through theta ~ 0 stays on the exact solution (chart switch)",
          "[simulate][gimbal]") {
    // Issue goal: tracked to the exact solution within 1e-8 over 100 time units at rtol 1e-10.
    // Started in the Lagrangian form; rotgen switches to the body form when |sin theta| < 0.1.
    const std::array<double, 3> I{1, 2, 3};
    for (const std::string start : {"theta: 0.5", "theta: 0"}) {
        const scratch_file scene(
            "tumble.yaml",
            scene_text(
                "free_asymmetric_top",
                "form: lagrangian\ninitial: {phi: 0, psi: 0, " + start +
                    ", omega1: 0.05, omega2: 0.5, omega3: 1}\ntime: {end: 100, samples: 2001}\n"
                    "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}\n"
                    "record: [omega1, omega2, omega3, theta]\n"));
        const run_result r =
            run_rotgen("simulate '" + scene.path + "' -o '" + scratch("tumble.csv") + "'");
        INFO(start << "\n" << r.out << r.err);
        REQUIRE(r.status == 0);
        CHECK(r.out.find("chart   ") != std::string::npos);
        const csv_table t = read_csv(scratch("tumble.csv"));
        const auto th = t.values("theta");
        CHECK(*std::min_element(th.begin(), th.end()) < 0.02); // it does pass close to theta = 0
        const rotgen::free_top_exact<double> exact(I, {0.05, 0.5, 1});
        double worst = 0;
        const auto ts = t.values("t");
        for (std::size_t i = 0; i < ts.size(); ++i) {
            const auto w = exact(ts[i]);
            for (int k = 0; k < 3; ++k)
                worst =
                    std::max(worst, std::abs(t.rows[i][1 + k] - w[static_cast<std::size_t>(k)]));
        }
        // measured 1.2e-9 from theta = 0 (the run changes chart about 45 times: to the body form
        // below |sin theta| 0.1, back above 0.3; each restart adds its own error; staying in the
        // body form gave 2.1e-10 and 3.1e-10); the goal is 1e-8
        CHECK(worst < 4e-9);
    }
}

TEST_CASE("bad scenes: exit 2, one line naming file and place, no output file",
          "[simulate][errors]") {
    using row = std::tuple<std::string, std::string, std::string>;
    const auto [name, body, expected] = GENERATE(table<std::string, std::string, std::string>({
        row{"NaN initial value",
            "initial: {theta: .nan, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\ntime: "
            "{end: 1}\n",
            "bad_scene.yaml:2:18: initial theta must be a finite number"},
        row{"theta out of range",
            "initial: {theta: 4, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\ntime: "
            "{end: 1}\n",
            "bad_scene.yaml:2:18: initial theta = 4"},
        row{"end equal to the start",
            "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\ntime: "
            "{start: 2, end: 2}\n",
            "bad_scene.yaml:3:23: time end must differ from time start (an end before the start "
            "runs backward in time)"},
        row{"non-positive rtol",
            "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\ntime: "
            "{end: 1}\nintegrator: {method: dopri5, rtol: 0}\n",
            "bad_scene.yaml:4:36: integrator rtol must be positive"},
        row{"negative step",
            "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\ntime: "
            "{end: 1}\nintegrator: {method: rk4, step: -0.1}\n",
            "bad_scene.yaml:4:33: integrator step must be positive"},
        row{"fixed step without a step",
            "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\ntime: "
            "{end: 1}\nintegrator: {method: rk4}\n",
            "bad_scene.yaml:4:13: integrator rk4 is fixed-step and needs 'step'"},
        row{"a step and a tolerance",
            "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\ntime: "
            "{end: 1}\nintegrator: {method: dop853, step: 0.1, rtol: "
            "1e-8}\n",
            "bad_scene.yaml:4:47: integrator dop853 with a fixed step has no error control: give "
            "'step' or 'rtol', not both"},
        row{"unknown method",
            "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\ntime: "
            "{end: 1}\nintegrator: {method: dopri}\n",
            "did you mean 'dopri5'?"},
        row{"unknown record",
            "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\ntime: "
            "{end: 1}\nrecord: [thetta]\n",
            "bad_scene.yaml:4:10: cannot record 'thetta'; did you mean 'theta'?"},
        row{"rates given two ways", "initial: {theta: 1, psi_dot: 1, omega1: 2}\ntime: {end: 1}\n",
            "give the initial rates one way only"},
        row{"unknown parameter override",
            "parameters: {I2: 3}\ninitial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, "
            "psi_dot: 0}\ntime: {end: 1}\n",
            "unknown field 'I2' in parameters"},
        row{"missing time",
            "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\n",
            "bad_scene.yaml:1:1: missing field 'time'"},
        row{"unknown form",
            "form: euler\ninitial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: "
            "0}\ntime: {end: 1}\n",
            "unknown form 'euler'"},
        row{"record not in the form",
            "form: reduced\ninitial: {theta: 1, psi_dot: 3, phi: 0, psi: 0, phi_dot: 0, theta_dot: "
            "0}\ntime: {end: 1}\nrecord: [phi]\n",
            "bad_scene.yaml:5:10: the reduced form does not give 'phi'"},
        // Finite initial values whose consequences overflow double precision (a silent inf before).
        row{"initial rate overflows f",
            "initial: {theta: 1, phi_dot: 1e300, phi: 0, psi: 0, theta_dot: 0, psi_dot: 0}\ntime: "
            "{end: 1}\n",
            "bad_scene.yaml:2:10: initial values too large for double precision: theta_ddot = inf "
            "in f(t0, y0) at t = 0.0"},
        row{"initial momentum overflows f",
            "form: hamiltonian\ninitial: {theta: 1, p_psi: 1e300, phi: 0, psi: 0, p_phi: 0, "
            "p_theta: 0}\ntime: {end: 1}\n",
            "bad_scene.yaml:3:10: initial values too large for double precision: p_theta_dot = inf "
            "in f(t0, y0)"},
        row{"initial momentum overflows",
            "parameters: {I1: 4}\ninitial: {theta: 1, phi_dot: 1e308, phi: 0, psi: 0, theta_dot: "
            "0, psi_dot: 0}\ntime: {end: 1}\n",
            "bad_scene.yaml:3:10: initial values too large for double precision: p_phi = inf at t "
            "= 0.0"},
        row{"initial energy overflows",
            "parameters: {I1: 1e10, I3: 5e9}\nform: body\ninitial: {theta: 1, omega1: "
            "1e150, phi: 0, psi: 0, omega2: 0, omega3: 0}\ntime: {end: 1}\n",
            "bad_scene.yaml:4:10: initial values too large for double precision: energy = inf at t "
            "= 0.0"},
    }));
    INFO(name);
    const scratch_file scene("bad_scene.yaml", scene_text("heavy_top", body));
    const std::string csv = scratch("bad_scene.csv");
    std::remove(csv.c_str());
    const run_result r = run_rotgen("simulate bad_scene.yaml -o '" + csv + "'", ROTGEN_BINARY_DIR);
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.rfind("rotgen: error: ", 0) == 0);
    CHECK(r.err.find(expected) != std::string::npos);
    CHECK(read_file(csv).empty()); // no output file
}

TEST_CASE("a rate that comes out subnormal from omega is no internal error", "[simulate][errors]") {
    // phi_dot = omega1 sin(psi) / sin(theta) = 1e-300 * 1e-10 / sin(1): a subnormal number, which
    // GiNaC::numeric(double) refuses (CLN has no subnormal floats): "internal error: floating
    // point underflow" before.
    const scratch_file scene(
        "subnormal_scene.yaml",
        scene_text("heavy_top",
                   "initial: {theta: 1, psi: 1e-10, omega1: 1e-300, omega3: 1, phi: 0, omega2: 0}\n"
                   "time: {end: 1, samples: 3}\nrecord: [phi_dot, energy]\n"));
    const std::string csv = scratch("subnormal.csv");
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const csv_table t = read_csv(csv);
    REQUIRE(t.rows.size() == 3);
    const double phi_dot = t.values("phi_dot").front();
    CHECK(std::fpclassify(phi_dot) == FP_SUBNORMAL);
    // a subnormal near 1e-310 carries 43 significant bits (relative spacing 1.1e-13)
    CHECK(phi_dot == Approx(1e-310 / std::sin(1.0)).epsilon(1e-12));
    CHECK(std::isfinite(t.values("energy").back()));
}

TEST_CASE("an unwritable output path is a clear error before any work", "[simulate][errors]") {
    const run_result r =
        run_rotgen("simulate '" + std::string(ROTGEN_SOURCE_DIR) +
                   "/models/scenes/heavy_top_nutation.yaml' -o /nonexistent/dir/out.csv");
    CHECK(r.status == 2);
    CHECK(r.err ==
          "rotgen: error: /nonexistent/dir/out.csv: cannot write: No such file or directory\n");
}

TEST_CASE("an integration that cannot go on exits 3 and keeps its samples in a partial file",
          "[simulate][errors]") {
    // The damped top falls to theta = pi, where the Euler-angle forms are singular.
    const scratch_file scene(
        "falling_scene.yaml",
        scene_text("damped_driven_top",
                   "initial: {theta: 1.0, psi_dot: 5, phi: 0, psi: 0, phi_dot: 0, theta_dot: "
                   "0}\ntime: {end: 40, samples: 401}\n"
                   "integrator: {method: dopri5, rtol: 1e-8, atol: 1e-10}\nrecord: [theta]\n"));
    const std::string csv = scratch("falling.csv"), partial = scratch("falling.partial.csv");
    std::remove(csv.c_str());
    std::remove(partial.c_str());
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'");
    INFO(r.out << r.err);
    CHECK(r.status == 3);
    CHECK(r.err.find("falling_scene.yaml:4:13: the run stopped at t = ") != std::string::npos);
    CHECK(r.err.find("samples computed so far are in " + partial) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(std::ifstream(csv).good()); // never under the requested name
    const csv_table t = read_csv(partial);
    REQUIRE(t.rows.size() > 100);
    CHECK(t.rows.size() < 401);
    CHECK(t.values("theta").back() > 3.0); // it got close to pi before stopping
}

namespace {

// Runs a free-top scene (body form, omega only) and returns the CSV.
csv_table run_free_top(const std::string& model, const std::string& initial, double end,
                       long samples, const std::string& name,
                       const std::string& integrator = "{method: dop853, rtol: 1e-12, atol: 1e-14}",
                       std::string* summary = nullptr) {
    const scratch_file scene(name + ".yaml", model + "form: body\ninitial: {phi: 0, psi: 0, " +
                                                 initial + "}\ntime: {end: " + std::to_string(end) +
                                                 ", samples: " + std::to_string(samples) +
                                                 "}\nintegrator: " + integrator +
                                                 "\n"
                                                 "record: [omega1, omega2, omega3]\n");
    const run_result r =
        run_rotgen("simulate '" + scene.path + "' -o '" + scratch(name + ".csv") + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    if (summary) *summary = r.out;
    return read_csv(scratch(name + ".csv"));
}

// Mean period of a signal from its upward zero crossings (linear interpolation between samples).
double mean_period(const std::vector<double>& t, const std::vector<double>& x) {
    std::vector<double> crossings;
    for (std::size_t i = 1; i < x.size(); ++i)
        if (x[i - 1] < 0 && x[i] >= 0)
            crossings.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-x[i - 1]) / (x[i] - x[i - 1]));
    REQUIRE(crossings.size() >= 3);
    return (crossings.back() - crossings.front()) / double(crossings.size() - 1);
}

} // namespace

TEST_CASE("steady rotation: frequencies (5.94) about axes 1 and 3, growth (5.100) about axis 2",
          "[simulate][stability]") {
    // I = (1, 2, 3), spin 1 about each axis, perturbation 1e-6. (The chapter orders I1 > I2 > I3;
    // the formulas are symmetric, here axis 1 has the smallest moment.)
    const double I1 = 1, I2 = 2, I3 = 3, spin = 1, eps = 1e-6;
    const std::string model = "model: " + model_path("free_asymmetric_top") + "\n";
    const double pi = 3.141592653589793;

    SECTION("axis 1: oscillation at Omega1") {
        const double omega1 = std::sqrt((I1 - I3) * (I1 - I2) / (I2 * I3)) * spin;
        const csv_table t = run_free_top(model, "theta: 1, omega1: 1, omega2: 1e-6, omega3: 1e-6",
                                         60, 6001, "stable1");
        const double measured = 2 * pi / mean_period(t.values("t"), t.values("omega2"));
        CHECK(measured == Approx(omega1).epsilon(0.01));
        const auto w2 = t.values("omega2");
        CHECK(*std::max_element(w2.begin(), w2.end()) < 10 * eps); // stays small
    }
    SECTION("axis 3: oscillation at Omega3") {
        const double omega3 = std::sqrt((I1 - I3) * (I2 - I3) / (I1 * I2)) * spin;
        const csv_table t = run_free_top(model, "theta: 1, omega1: 1e-6, omega2: 1e-6, omega3: 1",
                                         60, 6001, "stable3");
        const double measured = 2 * pi / mean_period(t.values("t"), t.values("omega1"));
        CHECK(measured == Approx(omega3).epsilon(0.01));
    }
    SECTION("axis 2: exponential growth at Omega2") {
        const double omega2 = std::sqrt((I1 - I2) * (I2 - I3) / (I1 * I3)) * spin;
        const csv_table t = run_free_top(model, "theta: 1, omega1: 1e-6, omega2: 1, omega3: 0", 16,
                                         1601, "unstable2");
        // While the deviation is small, omega1 and omega3 grow like exp(Omega2 t): fit the
        // slope of log|omega1| over the samples with 1e-5 < |omega1| < 1e-2 (past the
        // transient of the decaying mode, before the nonlinear flip).
        const auto ts = t.values("t"), w1 = t.values("omega1");
        double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
        for (std::size_t i = 0; i < ts.size(); ++i)
            if (std::abs(w1[i]) > 1e-5 && std::abs(w1[i]) < 1e-2) {
                const double y = std::log(std::abs(w1[i]));
                sx += ts[i], sy += y, sxx += ts[i] * ts[i], sxy += ts[i] * y, n += 1;
            }
        REQUIRE(n > 50);
        const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
        CHECK(slope == Approx(omega2).epsilon(0.01));
    }
}

TEST_CASE("free symmetric top: omega precesses about the symmetry axis at (I3 - I1)/I1 omega3",
          "[simulate]") {
    // An inline model in the scene; I1 = I2 = 2, I3 = 1.
    const std::string model = "model:\n  name: symmetric\n  inertia: [2, 2, 1]\n";
    const double I1 = 2, I3 = 1, w3 = 3, w_perp = 0.4;
    const double Omega = (I3 - I1) / I1 * w3; // (omega1 + i omega2) ~ exp(-i Omega t)
    const csv_table t =
        run_free_top(model, "theta: 0.7, omega1: 0.4, omega2: 0, omega3: 3", 10, 101, "symmetric");
    const auto ts = t.values("t"), w1 = t.values("omega1"), w2 = t.values("omega2"),
               w3s = t.values("omega3");
    for (std::size_t i = 0; i < ts.size(); ++i) {
        // I1 omega1_dot = (I1 - I3) omega2 omega3, I1 omega2_dot = (I3 - I1) omega3 omega1:
        // omega1 = w_perp cos(Omega t), omega2 = w_perp sin(Omega t)
        CHECK(w1[i] == Approx(w_perp * std::cos(Omega * ts[i])).margin(1e-10));
        CHECK(w2[i] == Approx(w_perp * std::sin(Omega * ts[i])).margin(1e-10));
        CHECK(w3s[i] == Approx(w3).margin(1e-12));
    }
}

TEST_CASE("an adaptive method given a step takes fixed steps: no rejections, error falls as h^8",
          "[simulate]") {
    // The symmetric top of the test above, integrated by DOP853 with fixed steps h and h/2.
    const std::string model = "model:\n  name: symmetric\n  inertia: [2, 2, 1]\n";
    const double I1 = 2, I3 = 1, w3 = 3, w_perp = 0.4, Omega = (I3 - I1) / I1 * w3;
    std::array<double, 2> error{};
    for (int k = 0; k < 2; ++k) {
        const double h = k == 0 ? 0.5 : 0.25;
        std::string summary;
        const csv_table t = run_free_top(
            model, "theta: 0.7, omega1: 0.4, omega2: 0, omega3: 3", 10, 11, "fixed_dop853",
            "{method: dop853, step: " + std::to_string(h) + "}", &summary);
        INFO(summary);
        CHECK(summary.find(std::to_string(static_cast<int>(10 / h)) + " accepted, 0 rejected") !=
              std::string::npos);
        const auto ts = t.values("t"), w1 = t.values("omega1"), w2 = t.values("omega2");
        for (std::size_t i = 0; i < ts.size(); ++i)
            error[static_cast<std::size_t>(k)] =
                std::max({error[static_cast<std::size_t>(k)],
                          std::abs(w1[i] - w_perp * std::cos(Omega * ts[i])),
                          std::abs(w2[i] - w_perp * std::sin(Omega * ts[i]))});
    }
    INFO("errors " << error[0] << " " << error[1]);
    CHECK(error[0] < 1e-6);
    // order 8: halving the step divides the error by 2^8 = 256 (asymptotically)
    CHECK(error[0] / error[1] > 128);
    CHECK(error[0] / error[1] < 512);
}

TEST_CASE("near gimbal lock the Hamiltonian chart loses accuracy and the switch keeps it",
          "[simulate][gimbal]") {
    // A free symmetric top (I = 2, 2, 1) whose symmetry axis starts 1e-4 from the vertical
    // (its closest approach; see bench/extremes/gimbal_lock.sh for 1e-1 ... 1e-8).
    // Exact: omega1 + i omega2 = 0.3 exp(-i t/2), omega3 = 1.
    const auto max_error = [](const std::string& switch_chart) {
        const scratch_file scene(
            "near_lock.yaml",
            "model:\n  name: symmetric_free_top\n  inertia: [2, 2, 1]\nform: hamiltonian\n"
            "switch_chart: " +
                switch_chart +
                "\ninitial: {phi: 0, theta: 1e-4, psi: 1.5707963267948966, omega1: 0.3, omega2: 0, "
                "omega3: "
                "1}\n"
                "time: {end: 40, samples: 401}\nintegrator: {method: dop853, rtol: 1e-10, atol: "
                "1e-12}\n"
                "record: [omega1, omega2, omega3]\n");
        const run_result r =
            run_rotgen("simulate '" + scene.path + "' -o '" + scratch("near_lock.csv") + "'");
        INFO(r.out << r.err);
        REQUIRE(r.status == 0);
        const csv_table t = read_csv(scratch("near_lock.csv"));
        double worst = 0;
        for (const auto& row : t.rows) {
            worst = std::max(worst, std::abs(row[1] - 0.3 * std::cos(-0.5 * row[0])));
            worst = std::max(worst, std::abs(row[2] - 0.3 * std::sin(-0.5 * row[0])));
            worst = std::max(worst, std::abs(row[3] - 1));
        }
        return worst;
    };
    const double kept = max_error("false"), switched = max_error("true");
    CHECK(switched < 1e-9);
    // measured: 3.4e-8 vs 1.3e-10 (the switched run changes chart 7 times: to the body form below
    // |sin theta| 0.1 and back above 0.3; without the switch back it was 4.5e-11)
    CHECK(kept > 100 * switched);
}

TEST_CASE("a reduced scene without record: records what the form gives (no ignored angle)",
          "[simulate][reduced]") {
    // Before: "the reduced form does not give 'phi'", because the default record (phi, theta, psi,
    // energy) ignored the form. The heavy top drops phi and psi (both cyclic), the free asymmetric
    // top only phi (psi appears in T through I1 != I2).
    // drift: the bound on max |E(t) - E(0)|, 10x the observed 4.4e-12 and 6.0e-10.
    using row = std::tuple<std::string, std::vector<std::string>, double>;
    const auto [model, header, drift] =
        GENERATE(table<std::string, std::vector<std::string>, double>({
            row{"heavy_top", {"t", "theta", "energy"}, 5e-11},
            row{"free_asymmetric_top", {"t", "theta", "psi", "energy"}, 6e-9},
        }));
    INFO(model);
    const scratch_file scene(
        "reduced_default_scene.yaml",
        scene_text(model,
                   "form: reduced\n"
                   "initial: {theta: 1, psi: 0.3, phi_dot: 0.5, psi_dot: 3, phi: 0, theta_dot: 0}\n"
                   "time: {end: 2, samples: 21}\n"
                   "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}\n"));
    const std::string csv = scratch("reduced_default.csv");
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const csv_table t = read_csv(csv);
    CHECK(t.header == header);
    REQUIRE(t.rows.size() == 21);
    CHECK(t.values("theta").front() == 1.0);
    // A conservative model: the energy stays (dop853 at rtol 1e-10).
    CHECK(max_abs_change(t.values("energy")) < drift);
}
