// Scene events end to end (scene/events.hpp, run/event_kernels.hpp, simulate's events CSV): the
// heavy top's turning points against the roots of the chapter's cubic in u = cos theta and the
// nutation half-period (an elliptic integral); the shipped falling top stopped at theta = pi/2;
// every form and the chart switch; `inspect` of a scene.
#include "support.hpp"

#include <boost/math/special_functions/ellint_1.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

using namespace rotgen::test;

namespace {

std::string scratch(const std::string& name) {
    return std::string(ROTGEN_BINARY_DIR) + "/" + name;
}

// The first column (event names) of an events CSV (after its provenance line and header).
std::vector<std::string> event_names(const std::string& path) {
    std::istringstream in(without_provenance(read_file(path)));
    std::string line;
    std::vector<std::string> names;
    std::getline(in, line);
    while (std::getline(in, line))
        names.push_back(line.substr(0, line.find(',')));
    return names;
}

// The time the heavy top without spin (a pendulum about its inverted position, 5.73 with
// phi_dot = psi_dot = 0: I1 theta_ddot = M g h sin theta) takes to fall from rest at theta0 to
// theta. With alpha = pi - theta measured from below, sin(alpha/2) = k sn(w t' + K, k),
// k = sin(alpha0/2) = cos(theta0/2), w^2 = M g h / I1 (the pendulum; Lawden, Elliptic Functions
// and Applications, §5.2), so t = (K(k) - F(asin(cos(theta/2)/k), k)) / w.
double fall_time(double theta0, double theta) {
    const double k = std::cos(theta0 / 2), w = std::sqrt(9.81 * 0.1 / 1.0); // heavy_top.yaml
    return (boost::math::ellint_1(k) -
            boost::math::ellint_1(k, std::asin(std::cos(theta / 2) / k))) /
           w;
}

// `rotgen simulate` of the spinning heavy top over t in [0, 1] with `integrator` and the event
// `event` (a YAML mapping); the events CSV is scratch(<name>_events.csv).
run_result run_event_scene(const std::string& name, const std::string& integrator,
                           const std::string& event) {
    const scratch_file scene(
        name + ".yaml",
        "model: " + model_path("heavy_top") +
            "\ninitial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}\n"
            "time: {end: 1, samples: 3}\nintegrator: " +
            integrator + "\nrecord: [theta]\nevents: [" + event + "]\n");
    return run_rotgen("simulate '" + scene.path + "' -o '" + scratch(name + ".csv") +
                      "' --events '" + scratch(name + "_events.csv") + "'");
}

} // namespace

TEST_CASE("heavy top: theta_dot = 0 at the roots of the cubic in u = cos theta, every nutation "
          "half-period",
          "[simulate][events]") {
    const double I1 = 1.0, I3 = 0.5, M = 1.0, g = 9.81, h = 0.1; // models/heavy_top.yaml
    const double theta0 = 0.5, spin = 30;
    const scratch_file scene(
        "turning_scene.yaml",
        "model: " + model_path("heavy_top") +
            "\ninitial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}\ntime: "
            "{end: 5, samples: 11}\n"
            "integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}\n"
            "record: [theta, energy]\nevents: [{name: turn, when: theta_dot}]\n");
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + scratch("turn.csv") +
                                    "' --events '" + scratch("turn_events.csv") + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const csv_table ev = read_csv(scratch("turn_events.csv"));
    CHECK(ev.header == std::vector<std::string>{"event", "t", "phase", "theta", "energy"});
    REQUIRE(ev.rows.size() >= 10); // theta_dot = 0 at t0 is not an event
    // (5.79) with u = cos theta: u_dot^2 = f(u) = (beta - alpha u)(1 - u^2) - (b - a u)^2,
    // a = p_psi/I1, b = p_phi/I1, alpha = 2 M g h/I1, beta = 2 E'/I1, E' = E - p_psi^2/(2 I3):
    //   f(u) = alpha u^3 - (beta + a^2) u^2 + (2 a b - alpha) u + beta - b^2
    //        = alpha (u - u1)(u - u2)(u - u3),  u1 < u2 = cos theta0 < 1 < u3.
    const double p_psi = I3 * spin, p_phi = p_psi * std::cos(theta0);
    const double E = ev.values("energy").front();
    const double a = p_psi / I1, b = p_phi / I1, alpha = 2 * M * g * h / I1;
    const double beta = 2 * (E - p_psi * p_psi / (2 * I3)) / I1;
    const double u2 = std::cos(theta0);
    const double q1 = -(beta + a * a) + alpha * u2, q0 = (2 * a * b - alpha) + u2 * q1; // f/(u-u2)
    const double disc = std::sqrt(q1 * q1 - 4 * alpha * q0);
    const double u1 = (-q1 - disc) / (2 * alpha), u3 = (-q1 + disc) / (2 * alpha);
    REQUIRE(u1 < u2);
    REQUIRE(u3 > 1);
    // Half-period: the integral of du / sqrt(f) from u1 to u2 = 2 K(k) / sqrt(alpha (u3 - u1)),
    // k^2 = (u2 - u1)/(u3 - u1) (Byrd & Friedman, Handbook of Elliptic Integrals, 233.00).
    const double k = std::sqrt((u2 - u1) / (u3 - u1));
    const double half = 2 * boost::math::ellint_1(k) / std::sqrt(alpha * (u3 - u1));
    const double theta_max = std::acos(u1);
    const auto t = ev.values("t"), theta = ev.values("theta");
    double worst_t = 0, worst_theta = 0;
    for (std::size_t j = 0; j < t.size(); ++j) {
        worst_t = std::max(worst_t, std::abs(t[j] - double(j + 1) * half));
        worst_theta = std::max(worst_theta, std::abs(theta[j] - (j % 2 == 0 ? theta_max : theta0)));
    }
    CHECK(worst_t < 5e-12);     // observed 8.2e-13 over 23 turning points
    CHECK(worst_theta < 1e-13); // observed 1.2e-14
    CHECK(r.out.find("  event   turn: " + std::to_string(t.size()) + " times\n") !=
          std::string::npos);
}

TEST_CASE("the falling top stops at theta = pi/2: the event's row ends the samples",
          "[simulate][events]") {
    const std::string csv = scratch("falling.csv");
    const run_result r = run_rotgen("simulate '" + std::string(ROTGEN_SOURCE_DIR) +
                                    "/models/scenes/falling_top.yaml' -o '" + csv + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const csv_table samples = read_csv(csv), ev = read_csv(scratch("falling.events.csv"));
    CHECK(event_names(scratch("falling.events.csv")) ==
          std::vector<std::string>{"halfway", "floor"});
    REQUIRE(ev.rows.size() == 2);
    CHECK(ev.header ==
          std::vector<std::string>{"event", "t", "phase", "theta", "theta_dot", "energy"});
    // the last sample row is the terminal event's row, exactly; every earlier sample is before it
    std::vector<double> floor_row = {ev.rows[1][1], ev.rows[1][3], ev.rows[1][4], ev.rows[1][5]};
    CHECK(samples.rows.back() == floor_row);
    CHECK(samples.rows[samples.rows.size() - 2][0] < floor_row[0]);
    CHECK(samples.rows.size() == 244); // samples every 0.01 up to t = 2.43, then the event
    CHECK_THAT(ev.rows[0][3], Catch::Matchers::WithinAbs(M_PI / 4, 1e-14)); // observed 0
    CHECK_THAT(floor_row[1], Catch::Matchers::WithinAbs(M_PI / 2, 1e-14));  // observed 2.4e-15
    CHECK_THAT(ev.rows[0][1], Catch::Matchers::WithinAbs(fall_time(0.3, M_PI / 4), 1e-11));
    CHECK_THAT(floor_row[0], Catch::Matchers::WithinAbs(fall_time(0.3, M_PI / 2), 1e-11));
    // observed 1.3e-12 both; energy: (1/2) I1 theta_dot^2 = M g h (cos 0.3 - cos theta) (5.73)
    CHECK_THAT(floor_row[2], Catch::Matchers::WithinAbs(std::sqrt(2 * 0.981 * std::cos(0.3)),
                                                        5e-12)); // observed 5.3e-13
    CHECK(r.out.find("  event   halfway: 1 time\n") != std::string::npos);
    CHECK(r.out.find("  event   floor: 1 time; stopped the run at t = 2.4287803196") !=
          std::string::npos);
}

TEST_CASE("the Taylor method locates events on its own series", "[simulate][events]") {
    const scratch_file scene(
        "falling_taylor.yaml",
        "model: " + model_path("heavy_top") +
            "\ninitial: {phi: 0, theta: 0.3, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\n"
            "time: {end: 5, samples: 6}\nintegrator: {method: taylor, rtol: 1e-12, atol: 1e-12}\n"
            "record: [theta]\nevents: [{name: halfway, when: theta - pi/4, direction: rising}, "
            "{name: floor, when: theta - pi/2, direction: rising, action: stop}]\n");
    const run_result r =
        run_rotgen("simulate '" + scene.path + "' -o '" + scratch("falling_taylor.csv") + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const csv_table ev = read_csv(scratch("falling_taylor.events.csv"));
    REQUIRE(ev.rows.size() == 2);
    // observed 1.1e-14 (halfway) and 9.3e-15 (floor) against the pendulum's elliptic integral
    // (DOP853 at the same rtol: 1.3e-12, the test above)
    CHECK_THAT(ev.rows[0][1], Catch::Matchers::WithinAbs(fall_time(0.3, M_PI / 4), 1e-13));
    CHECK_THAT(ev.rows[1][1], Catch::Matchers::WithinAbs(fall_time(0.3, M_PI / 2), 1e-13));
    // theta there: the refinement stops at a bracket of 1e-14 |t| = 2.4e-14 in t, where
    // theta' = 1.38, so up to 3.4e-14 (observed 2.1e-14)
    CHECK_THAT(ev.rows[1][3], Catch::Matchers::WithinAbs(M_PI / 2, 4e-14));
}

TEST_CASE("events in every form and across the chart switch agree", "[simulate][events]") {
    // theta0 = 0.05 (|sin theta| < 0.1) starts the Euler-angle forms in the body form, which
    // returns to the scene's form above |sin theta| = 0.3 before the event.
    struct row {
        const char* form;
        double theta0, bound;
    };
    // the error of the event's time against the elliptic integral, observed beside each bound
    const row c =
        GENERATE(values<row>({{"lagrangian", 0.3, 3e-12},    // 2.7e-13
                              {"hamiltonian", 0.3, 3e-12},   // 2.7e-13
                              {"reduced", 0.3, 1.5e-12},     // 1.5e-13
                              {"body", 0.3, 3.5e-12},        // 3.4e-13
                              {"lagrangian", 0.05, 1.2e-11}, // 1.2e-12, through the body form
                              {"body", 0.05, 1.3e-11}}));    // 1.3e-12
    CAPTURE(c.form, c.theta0);
    const scratch_file scene(
        "falling_forms.yaml",
        "model: " + model_path("heavy_top") + "\nform: " + c.form +
            "\ninitial: {phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0, theta: " +
            std::to_string(c.theta0) +
            "}\ntime: {end: 6, samples: 7}\n"
            "integrator: {method: dop853, rtol: 1e-12, atol: 1e-12}\nrecord: [theta, energy]\n"
            "events: [{name: floor, when: theta - pi/2, direction: rising, action: stop}]\n");
    const run_result r =
        run_rotgen("simulate '" + scene.path + "' -o '" + scratch("falling_forms.csv") + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK((r.out.find("chart") != std::string::npos) == (c.theta0 < 0.1 && c.form[0] == 'l'));
    const csv_table ev = read_csv(scratch("falling_forms.events.csv"));
    REQUIRE(ev.rows.size() == 1);
    CHECK_THAT(ev.rows[0][1], Catch::Matchers::WithinAbs(fall_time(c.theta0, M_PI / 2), c.bound));
}

TEST_CASE("inspect of a scene lists its event functions", "[inspect][events]") {
    const std::string scene = std::string(ROTGEN_SOURCE_DIR) + "/models/scenes/falling_top.yaml";
    const run_result text = run_rotgen("inspect '" + scene + "'");
    INFO(text.out << text.err);
    REQUIRE(text.status == 0);
    CHECK(text.out.find("Lagrangian") != std::string::npos); // the model's equations first
    CHECK(text.out.find("\nEvents (zeros of g, scene)\n"
                        "  halfway: -pi/4 + theta = 0, rising, record\n"
                        "  floor: -pi/2 + theta = 0, rising, stop\n") != std::string::npos);
    const run_result json = run_rotgen("inspect '" + scene + "' --format json");
    REQUIRE(json.status == 0);
    CHECK(json.out.find(",\n  \"events\": [{\"name\": \"halfway\", \"when\": \"-pi/4 + theta\", "
                        "\"direction\": \"rising\", \"action\": \"record\"}, ") !=
          std::string::npos);
}

TEST_CASE("a scene finds all 318 zeros of sin(1000 t) for 0 < t <= 1 with every method",
          "[simulate][events]") {
    // g depends on t alone: its zeros are k pi / 1000 exactly, several in each step the top takes
    const std::string integrator =
        GENERATE(as<std::string>{}, "{method: dop853, rtol: 1e-6, atol: 1e-6}",
                 "{method: dop853, rtol: 1e-10, atol: 1e-10}",
                 "{method: taylor, rtol: 1e-10, atol: 1e-10}", "{method: rk4, step: 0.01}");
    INFO(integrator);
    const run_result r = run_event_scene("fast", integrator, "{name: fast, when: sin(1000*t)}");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("event   fast: 318 times") != std::string::npos);
    CHECK(r.out.find("warning") == std::string::npos);
    const csv_table ev = read_csv(scratch("fast_events.csv"));
    REQUIRE(ev.rows.size() == 318);
    double worst = 0;
    for (std::size_t k = 0; k < ev.rows.size(); ++k)
        worst = std::max(worst, std::abs(ev.rows[k][1] - double(k + 1) * M_PI / 1000));
    CHECK(worst < 1e-13); // observed 1e-14
}

TEST_CASE("the summary names where a pair of zeros may hide: g = (t - 0.5)^2 touches 0",
          "[simulate][events]") {
    const run_result r = run_event_scene("touch", "{method: dop853, rtol: 1e-10, atol: 1e-10}",
                                         "{name: touch, when: (t - 0.5)*(t - 0.5)}");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("event   touch: 0 times") != std::string::npos);
    const std::string warning = "  warning event touch: a pair of zeros may hide in t = ";
    const auto at = r.out.find(warning);
    REQUIRE(at != std::string::npos);
    double from = 0, to = 0;
    REQUIRE(std::sscanf(r.out.c_str() + at + warning.size(), "%lf .. %lf", &from, &to) == 2);
    // the interval holds 0.5: observed [0.4999999999999894, 0.50000000000000699] under the error
    // per unit step (the steps, and so the search's brackets, moved; 5.6e-17 wide before)
    CHECK(from <= 0.5);
    CHECK(to >= 0.5 - 1.2e-16);
    CHECK(to - from < 2e-13); // observed 1.8e-14
    CHECK(r.out.find("(g neither changes sign nor stays away from 0 there)\n", at) !=
          std::string::npos);
}
