// Gyrostats (`wheels:`, derive/wheels.hpp) run through `rotgen simulate`, every sample against
// truth computed here:
//   * the axisymmetric gyrostat with a wheel on its symmetry axis, torque-free: omega3 and h are
//     constant and omega1 + i omega2 turns at Omega = ((I3 - I1) omega3 + h) / I1 (from
//     I omega' + omega x (I omega + h) = 0: omega1' = -Omega omega2, omega2' = Omega omega1, so
//     counter-clockwise for Omega > 0), and body axis 3 precesses about L (space) at |L| / I1
//     (e3' = omega x e3 = L x e3 / I1, since I1 omega = L - (h + (I3 - I1) omega3) e3): in the
//     lagrangian, hamiltonian, reduced and body forms and with the Taylor method;
//   * three skewed free wheels: L in space and the energy conserved;
//   * a wheel whose rate a motor holds: E(t) - E(0) = integral of the motor's power
//     tau omega_rel = p_wheel' wheel_dot;
//   * an intermediate-axis spin: the wobble grows below the h/omega threshold that
//     `inspect --inertia` reports and stays small above it;
//   * bad wheels and the split methods: exit 2, one located line.
#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

using namespace rotgen::test;

namespace {

csv_table run_scene(const std::string& name, const std::string& text) {
    const scratch_file scene(name + ".yaml", text);
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/" + name + ".csv";
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    csv_table t = read_csv(csv);
    std::remove(csv.c_str());
    return t;
}

// I1 = I2 = 2, I3 = 3, J = 0.2 on body axis 3, p_wheel = 0.7.
const std::string axisymmetric_model = R"(model:
  name: axisymmetric_gyrostat
  parameters: {I1: 2.0, I3: 3.0, Jw: 0.2}
  inertia: [I1, I1, I3]
  wheels:
    - {name: wheel, axis: [0, 0, 2], inertia: Jw}
)";

using vec = std::array<double, 3>;

vec cross(const vec& a, const vec& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const vec& a, const vec& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

struct axisymmetric_truth {
    double I1 = 2, I3 = 3, h = 0.7, phi = 0.3, theta = 0.8, psi = 0.2;
    vec w0{0.4, -0.3, 1.1};
    double Omega() const { return ((I3 - I1) * w0[2] + h) / I1; }
    vec omega(double t) const {
        const double c = std::cos(Omega() * t), s = std::sin(Omega() * t);
        return {w0[0] * c - w0[1] * s, w0[0] * s + w0[1] * c, w0[2]};
    }
    // theta(t): e3 (third row of A, 5.25) turned about L (space) by |L| t / I1 (Rodrigues).
    double theta_at(double t) const {
        const double cf = std::cos(phi), sf = std::sin(phi), ct = std::cos(theta),
                     st = std::sin(theta), cp = std::cos(psi), sp = std::sin(psi);
        const double A[3][3] = {{cp * cf - ct * sf * sp, cp * sf + ct * cf * sp, sp * st},
                                {-sp * cf - ct * sf * cp, -sp * sf + ct * cf * cp, cp * st},
                                {st * sf, -st * cf, ct}};
        const vec lb{I1 * w0[0], I1 * w0[1], I3 * w0[2] + h};
        vec L{0, 0, 0}, e3{A[2][0], A[2][1], A[2][2]};
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i)
                L[j] += A[i][j] * lb[i];
        const double n = std::sqrt(dot(L, L)), a = n * t / I1;
        const vec k{L[0] / n, L[1] / n, L[2] / n}, kx = cross(k, e3);
        const double kv = dot(k, e3);
        return std::acos(e3[2] * std::cos(a) + kx[2] * std::sin(a) + k[2] * kv * (1 - std::cos(a)));
    }
};

std::string axisymmetric_scene(const std::string& form, const std::string& method) {
    const bool reduced = form == "reduced";
    return axisymmetric_model + "form: " + form +
           (form == "hamiltonian" ? "\nswitch_chart: false" : "") +
           "\ninitial: {phi: 0.3, theta: 0.8, psi: 0.2, omega1: 0.4, omega2: -0.3, omega3: 1.1, "
           "p_wheel: 0.7}\ntime: {start: 0, end: 20, samples: 201}\nintegrator: {method: " +
           method + ", rtol: 1e-12, atol: 1e-12}\nrecord: " +
           (reduced ? "[theta]" : "[theta, omega1, omega2, omega3, p_wheel, h3, wheel_dot]") + "\n";
}

} // namespace

TEST_CASE("axisymmetric gyrostat: omega1 + i omega2 turns at ((I3 - I1) omega3 + h) / I1 in every "
          "form",
          "[wheels]") {
    const axisymmetric_truth truth;
    REQUIRE(truth.Omega() == Approx(0.9)); // (1 * 1.1 + 0.7) / 2: counter-clockwise
    for (const auto& [form, method] :
         std::vector<std::pair<std::string, std::string>>{{"lagrangian", "dop853"},
                                                          {"hamiltonian", "dop853"},
                                                          {"reduced", "dop853"},
                                                          {"body", "dop853"},
                                                          {"lagrangian", "taylor"}}) {
        INFO(form << " " << method);
        const csv_table t = run_scene("wheels_axisym", axisymmetric_scene(form, method));
        REQUIRE(t.rows.size() == 201);
        double worst_w = 0, worst_theta = 0, worst_p = 0;
        for (const auto& r : t.rows) {
            const double time = r[t.column("t")];
            worst_theta =
                std::max(worst_theta, std::abs(r[t.column("theta")] - truth.theta_at(time)));
            if (form == "reduced") continue;
            const vec w = truth.omega(time);
            for (int i = 0; i < 3; ++i)
                worst_w = std::max(worst_w,
                                   std::abs(r[t.column("omega" + std::to_string(i + 1))] - w[i]));
            worst_p = std::max({worst_p, std::abs(r[t.column("p_wheel")] - truth.h),
                                std::abs(r[t.column("h3")] - truth.h),
                                std::abs(r[t.column("wheel_dot")] - (truth.h / 0.2 - w[2]))});
        }
        CHECK(worst_w < 1e-10);     // observed up to 6.9e-12 (hamiltonian)
        CHECK(worst_theta < 5e-11); // observed up to 3.6e-12 (body)
        CHECK(worst_p < 1e-11);     // observed up to 7.8e-13 (wheel_dot from omega3)
    }
}

namespace {

// A full tensor with three free wheels on skewed axes (not unit: normalised by the reader).
const std::string three_wheels_model = R"(model:
  name: three_wheels
  parameters: {A: 2.0, B: 3.0, C: 4.5, D: 0.2, Jw: 0.1}
  inertia: [[A, D, 0], [D, B, -D], [0, -D, C]]
  wheels:
    - {name: w1, axis: [1, 0.2, 0], inertia: Jw}
    - {name: w2, axis: [0, 1, 0.3], inertia: Jw}
    - {name: w3, axis: [0.1, -0.2, 1], inertia: Jw}
)";

} // namespace

TEST_CASE("three skewed free wheels: total L in space and the energy are conserved", "[wheels]") {
    for (const std::string form : {"lagrangian", "body"}) {
        INFO(form);
        const csv_table t = run_scene(
            "wheels_three", three_wheels_model + "form: " + form +
                                "\nswitch_chart: true\ninitial: {phi: 0.3, theta: 1.0, psi: 0.2, "
                                "omega1: 0.5, omega2: -0.4, omega3: 0.9, p_w1: 0.3, p_w2: -0.5, "
                                "p_w3: 0.8}\ntime: {start: 0, end: 200, samples: 401}\nintegrator: "
                                "{method: dop853, rtol: 1e-11, atol: 1e-12}\nrecord: [Lx, Ly, Lz, "
                                "energy, T, h1, h2, h3]\n");
        const auto& r0 = t.rows.front();
        double drift_L = 0, drift_E = 0;
        for (const auto& r : t.rows) {
            for (const char* n : {"Lx", "Ly", "Lz"})
                drift_L = std::max(drift_L, std::abs(r[t.column(n)] - r0[t.column(n)]));
            drift_E = std::max(drift_E, std::abs(r[t.column("energy")] - r0[t.column("energy")]));
            CHECK(r[t.column("T")] == Approx(r[t.column("energy")]).margin(1e-14)); // V = 0
        }
        // h in body axes: J-weighted axes, constant
        CHECK(r0[t.column("h1")] == Approx(0.3 / std::sqrt(1.04) + 0.1 * 0.8 / std::sqrt(1.05)));
        // the L the wheels add: |L| differs from the bare body's
        CHECK(std::abs(r0[t.column("Lz")]) > 0.1);
        CHECK(drift_L < 1e-9);  // observed 4.9e-11 (lagrangian), 9.6e-11 (body)
        CHECK(drift_E < 5e-10); // observed 2.3e-11 (lagrangian), 4.7e-11 (body)
    }
}

TEST_CASE("a wheel whose rate a motor holds: the energy changes by the motor's work", "[wheels]") {
    // T = 1/2 omega . I omega + 1/2 J (omega3 + W sin(2 t))^2; the motor's torque on the wheel is
    // p_wheel' and its power p_wheel' wheel_dot: E(t) - E(0) = integral p_wheel' wheel_dot dt.
    const csv_table t = run_scene(
        "wheels_motor",
        "model:\n  name: motor\n  parameters: {A: 2.0, B: 3.0, C: 4.0, Jw: 0.3, W: 2.0}\n  "
        "inertia: [A, B, C]\n  wheels:\n    - {name: wheel, axis: [0.2, 0, 1], inertia: Jw, drive: "
        "{rate: \"W*sin(2*t)\"}}\nform: lagrangian\ninitial: {phi: 0.3, theta: 1.0, psi: 0.2, "
        "omega1: 0.5, omega2: -0.4, omega3: 0.9}\ntime: {start: 0, end: 10, samples: 20001}\n"
        "integrator: {method: dop853, rtol: 1e-12, atol: 1e-12}\nrecord: [energy, p_wheel, "
        "wheel_dot, Lx, Ly, Lz]\n");
    const auto e = t.values("energy"), p = t.values("p_wheel"), r = t.values("wheel_dot"),
               time = t.values("t");
    double work = 0, worst = 0, change = 0;
    for (std::size_t i = 1; i < e.size(); ++i) {
        work += (p[i] - p[i - 1]) * (r[i] + r[i - 1]) / 2; // trapezoid of wheel_dot dp
        worst = std::max(worst, std::abs(e[i] - e[0] - work));
        change = std::max(change, std::abs(e[i] - e[0]));
        CHECK(r[i] == Approx(2 * std::sin(2 * time[i])).margin(1e-12));
    }
    CHECK(change > 0.05); // the motor does work: observed 0.61
    CHECK(worst < 5e-8);  // observed 7.6e-9 (the trapezoid's error at dt = 5e-4)
    // L in space is conserved: the motor's torque is internal
    const auto lx = t.values("Lx");
    CHECK(std::abs(lx.back() - lx.front()) < 1e-11); // observed 1.0e-12
}

namespace {

// The largest angle between body axis 2 and its start (space z) over a run of the satellite spun
// about its intermediate axis with wheel momentum p.
double largest_tilt(double p) {
    const csv_table t = run_scene(
        "wheels_tilt", "model: " + std::string(ROTGEN_SOURCE_DIR) +
                           "/models/gyrostat_satellite.yaml\nform: body\ninitial: {phi: 0, theta: "
                           "pi/2, psi: 0, omega1: 0.01, omega2: 1, omega3: 0.01, p_wheel: " +
                           std::to_string(p) +
                           "}\ntime: {start: 0, end: 150, samples: 1501}\nintegrator: {method: "
                           "dop853, rtol: 1e-10, atol: 1e-12}\nrecord: [body_y]\n");
    double worst = 0;
    for (double z : t.values("body_y_z"))
        worst = std::max(worst, std::acos(std::min(1.0, z)));
    return worst * 180 / 3.141592653589793;
}

} // namespace

TEST_CASE("intermediate-axis spin: the wobble stays small exactly beyond the threshold inspect "
          "reports",
          "[wheels]") {
    const run_result r =
        run_rotgen("inspect '" + model_path("gyrostat_satellite") + "' --inertia --format json");
    INFO(r.err);
    REQUIRE(r.status == 0);
    // axis 2 (I = 2, 3, 4): unstable for I1 - I2 = -1 < h/omega < I3 - I2 = 1
    CHECK(r.out.find("{\"axis\": 2, \"unstable_from\": \"I1 - I2\", \"unstable_to\": \"-I2 + "
                     "I3\", \"unstable_from_value\": -1.0, \"unstable_to_value\": 1.0}") !=
          std::string::npos);
    CHECK(r.out.find("\"wheels\": [{\"name\": \"wheel\", \"axis\": [\"0\", \"1\", \"0\"], "
                     "\"inertia\": \"Jw\", \"drive\": \"free\"}]") != std::string::npos);
    // h/omega = p_wheel / omega2 with omega2 = 1
    for (double p : {-0.8, -0.5, 0.0, 0.5, 0.8}) {
        INFO("p_wheel " << p);
        CHECK(largest_tilt(p) > 30); // observed 64, 101, 180, 82, 47 degrees
    }
    for (double p : {-1.3, -1.2, 1.2, 1.5, 3.0}) {
        INFO("p_wheel " << p);
        CHECK(largest_tilt(p) < 10); // observed 4.2, 4.5, 2.0, 1.5, 0.8 degrees
    }
}

TEST_CASE("bad wheels: exit 2, one line naming file and place", "[wheels]") {
    const auto refused = [](const std::string& wheels, const std::string& where,
                            const std::string& what) {
        const scratch_file m("wheels_bad.yaml", "name: bad\nparameters: {Jw: 0.1, Ia: 1.0}\n"
                                                "inertia: [Ia, Ia, Ia]\n" +
                                                    wheels);
        const run_result r = run_rotgen("inspect '" + m.path + "'");
        INFO(r.err);
        CHECK(r.status == 2);
        CHECK(r.err.find("wheels_bad.yaml:" + where + ": ") != std::string::npos);
        CHECK(r.err.find(what) != std::string::npos);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    };
    refused("wheels:\n  - {name: w, axis: [0, 0, 1], inertia: Jw, drive: spin}\n", "5:52",
            "unknown drive 'spin'");
    refused("wheels:\n  - {name: w, axis: [0, 0, 0], inertia: Jw}\n", "5:21", "is zero");
    refused("wheels:\n  - {name: w, axis: [0, 0, 1], inertia: Jw}\n  - {name: w, axis: [1, 0, 0], "
            "inertia: Jw}\n",
            "6:12", "already taken");
    refused("wheels:\n  - {name: Jw, axis: [0, 0, 1], inertia: Jw}\n", "5:12", "already taken");
    refused("wheels:\n  - {name: w, axis: [0, 0, 1], inertia: -Jw}\n", "5:41", "must be positive");
}

TEST_CASE("split methods refuse a model with wheels", "[wheels]") {
    const scratch_file scene("wheels_split.yaml",
                             axisymmetric_model +
                                 "initial: {phi: 0.3, theta: 0.8, psi: 0.2, omega1: 0.4, omega2: "
                                 "-0.3, omega3: 1.1}\ntime: {end: 1}\nintegrator: {method: split4, "
                                 "step: 0.01}\n");
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o -");
    CHECK(r.status == 2);
    CHECK(r.err.find("carries wheels") != std::string::npos);
}

TEST_CASE("simulate --from continues a gyrostat with the wheel's momentum from the row",
          "[wheels]") {
    // the model in a file of its own: --from checks that both runs are of the same model
    std::string model_text;
    std::istringstream in(axisymmetric_model);
    for (std::string line; std::getline(in, line);)
        if (line != "model:") model_text += line.substr(2) + "\n";
    const scratch_file model_file("wheels_from_model.yaml", model_text);
    const std::string scene =
        "model: " + model_file.path +
        "\nform: body\ninitial: {phi: 0.3, theta: 0.8, psi: 0.2, omega1: 0.4, "
        "omega2: -0.3, omega3: 1.1, p_wheel: 0.7}\ntime: {start: 0, end: 5, "
        "samples: 6}\nintegrator: {method: dop853, rtol: 1e-12, atol: "
        "1e-12}\nrecord: [q0, q1, q2, q3, omega1, omega2, omega3, p_wheel]\n";
    const scratch_file first("wheels_from1.yaml", scene);
    const std::string csv1 = std::string(ROTGEN_BINARY_DIR) + "/wheels_from1.csv",
                      csv2 = std::string(ROTGEN_BINARY_DIR) + "/wheels_from2.csv";
    REQUIRE(run_rotgen("simulate '" + first.path + "' -o '" + csv1 + "'").status == 0);
    // the same scene with the wheel at rest: --from must take p_wheel = 0.7 from the row
    std::string second_text = scene;
    second_text.replace(second_text.find("p_wheel: 0.7"), 12, "p_wheel: 0.0");
    second_text.replace(second_text.find("end: 5"), 6, "end: 9");
    const scratch_file second("wheels_from2.yaml", second_text);
    const run_result r =
        run_rotgen("simulate '" + second.path + "' --from '" + csv1 + "' -o '" + csv2 + "'");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const csv_table t = read_csv(csv2);
    std::remove(csv1.c_str());
    std::remove(csv2.c_str());
    const axisymmetric_truth truth;
    for (const auto& row : t.rows) {
        const vec w = truth.omega(row[t.column("t")]);
        CHECK(row[t.column("omega1")] == Approx(w[0]).margin(5e-12)); // observed 7.0e-13
        CHECK(row[t.column("p_wheel")] == Approx(0.7).margin(1e-12));
    }
}

TEST_CASE("rotgen sweep varies a free wheel's momentum like any parameter", "[wheels]") {
    const scratch_file scene(
        "wheels_sweep.yaml",
        "model: " + std::string(ROTGEN_SOURCE_DIR) +
            "/models/gyrostat_satellite.yaml\nform: body\ninitial: {phi: 0, theta: pi/2, psi: 0, "
            "omega1: 0.01, omega2: 1, omega3: 0.01}\ntime: {start: 0, end: 150, samples: 151}\n"
            "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}\nrecord: [body_y, p_wheel, "
            "h2]\nsweep:\n  mode: grid\n  vary: {parameters.p_wheel: {values: [0.5, 1.5, "
            "3.0]}}\n");
    const std::string dir = std::string(ROTGEN_BINARY_DIR) + "/wheels_sweep_out";
    std::filesystem::remove_all(dir);
    const run_result r = run_rotgen("sweep '" + scene.path + "' -o '" + dir + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const csv_table t = read_csv(dir + "/summary.csv");
    std::filesystem::remove_all(dir);
    REQUIRE(t.rows.size() == 3);
    const double p[3] = {0.5, 1.5, 3.0};
    for (std::size_t m = 0; m < 3; ++m) {
        CHECK(t.rows[m][t.column("final.p_wheel")] == Approx(p[m]).margin(1e-14));
        CHECK(t.rows[m][t.column("final.h2")] == Approx(p[m]).margin(1e-14));
    }
    // beyond the threshold h/omega = 1 body axis 2 stays up: observed 0.99978, 0.99995
    CHECK(t.rows[1][t.column("final.body_y_z")] > 0.98);
    CHECK(t.rows[2][t.column("final.body_y_z")] > 0.98);
}

// Torque-driven wheels (`drive: {torque: ...}`), against truth computed here:
//   * three skewed wheels whose motors use t, omega, an angle and a rate, no external torque: the
//     total angular momentum in space is constant (the motor torques are internal), and the
//     energy changes by the motors' work, E(t) - E(0) = integral of sum_k tau_k alpha_dot_k dt
//     = integral of sum_k <wheel>_dot dp_k (p_k' = tau_k), in the lagrangian, hamiltonian and
//     body forms;
//   * the shipped reaction-wheel slew (models/scenes/reaction_wheel_slew.yaml) reaches its target;
//   * `initial` takes a wheel's rate <wheel>_dot instead of its momentum;
//   * the reduced form and the split methods are refused with one located line;
//   * sensitivities (a wheel's momentum is a state) against central differences.
namespace {

const std::string torque_model = R"yaml(model:
  name: torque_wheels_run
  parameters: {A: 2.0, B: 3.0, C: 4.5, D: 0.2, Jw: 0.1, k: 0.3}
  inertia: [[A, D, 0], [D, B, -D], [0, -D, C]]
  wheels:
    - {name: w1, axis: [1, 0.2, 0], inertia: Jw, drive: {torque: "k*sin(t) - 0.2*omega1"}}
    - {name: w2, axis: [0, 1, 0.3], inertia: Jw, drive: {torque: "0.4*cos(theta) + 0.1*phi_dot"}}
    - {name: w3, axis: [0.1, -0.2, 1], inertia: Jw, drive: {torque: "0.3*omega2*omega3 - 0.2*sin(psi)"}}
)yaml";

} // namespace

TEST_CASE("torque-driven wheels: L in space is conserved and the energy changes by the motors' "
          "work",
          "[wheels][torque]") {
    for (const std::string form : {"lagrangian", "hamiltonian", "body"}) {
        INFO(form);
        const csv_table t = run_scene(
            "torque_wheels_" + form,
            torque_model + "form: " + form + "\nswitch_chart: false\n" +
                "initial: {phi: 0.3, theta: 1.0, psi: 0.2, omega1: 0.5, omega2: -0.4, omega3: "
                "0.9, p_w1: 0.3, p_w2: -0.5, p_w3: 0.8}\ntime: {start: 0, end: 10, samples: "
                "10001}\nintegrator: {method: dop853, rtol: 1e-12, atol: 1e-12}\nrecord: [Lx, Ly, "
                "Lz, energy, p_w1, p_w2, p_w3, w1_dot, w2_dot, w3_dot]\n");
        const auto& r0 = t.rows.front();
        // The work to sample i by the trapezoid of sum wheel_dot dp over steps of `every` samples
        const auto work_to = [&](std::size_t i, std::size_t every) {
            double w = 0;
            for (std::size_t j = every; j <= i; j += every)
                for (const std::string k : {"w1", "w2", "w3"}) {
                    const std::size_t p = t.column("p_" + k), d = t.column(k + "_dot");
                    w += (t.rows[j][p] - t.rows[j - every][p]) *
                         (t.rows[j][d] + t.rows[j - every][d]) / 2;
                }
            return w;
        };
        double drift_L = 0, change = 0, p_change = 0;
        for (const auto& r : t.rows) {
            for (const char* n : {"Lx", "Ly", "Lz"})
                drift_L = std::max(drift_L, std::abs(r[t.column(n)] - r0[t.column(n)]));
            for (const char* n : {"p_w1", "p_w2", "p_w3"})
                p_change = std::max(p_change, std::abs(r[t.column(n)] - r0[t.column(n)]));
            change = std::max(change, std::abs(r[t.column("energy")] - r0[t.column("energy")]));
        }
        double worst = 0; // at every 1000th sample, the trapezoid's h^2 error extrapolated away
        for (std::size_t i = 1000; i < t.rows.size(); i += 1000) {
            const double w = (4 * work_to(i, 1) - work_to(i, 2)) / 3;
            const double e = t.rows[i][t.column("energy")] - r0[t.column("energy")];
            worst = std::max(worst, std::abs(e - w));
        }
        CHECK(p_change > 0.3); // the motors change the wheels' momenta: observed 0.83
        CHECK(change > 0.1);   // the motors do work: observed 3.6
        // observed 9.3e-14 (lagrangian), 8.6e-13 (hamiltonian), 2.0e-12 (body)
        CHECK(worst < 2e-11);
        CHECK(drift_L < 3e-11); // observed 2.0e-12 (lagrangian, body), 3.5e-12 (hamiltonian)
    }
}

TEST_CASE("the reaction-wheel slew reaches its target attitude from rest", "[wheels][torque]") {
    // models/scenes/reaction_wheel_slew.yaml: from yaw 60, pitch -30, roll 45 degrees at rest to
    // the space frame (87 degrees) by the PD law through the three wheels' motors.
    const std::string scene =
        std::string(ROTGEN_SOURCE_DIR) + "/models/scenes/reaction_wheel_slew.yaml";
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/reaction_wheel_slew.csv";
    const run_result r = run_rotgen("simulate '" + scene + "' -o '" + csv + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const csv_table t = read_csv(csv);
    std::remove(csv.c_str());
    const auto error = [&](std::size_t i) { // the angle of the attitude from the target
        return 2 * std::acos(std::min(1.0, std::abs(t.rows[i][t.column("q0")])));
    };
    double largest_L = 0, largest_p = 0;
    for (const auto& row : t.rows) {
        for (const char* n : {"Lx", "Ly", "Lz"})
            largest_L = std::max(largest_L, std::abs(row[t.column(n)]));
        largest_p = std::max(largest_p, std::abs(row[t.column("p_wheel_x")]));
    }
    CHECK(error(0) == Approx(1.5244).margin(1e-4)); // 87.3 degrees at the start
    CHECK(error(t.rows.size() / 4) > 0.05);         // still turning at t = 10: observed 0.083
    CHECK(error(t.rows.size() - 1) < 3e-5);         // at t = 40: observed 3.2e-6 rad
    CHECK(largest_p > 0.5);                         // the wheels took the turn: observed 0.67
    CHECK(std::abs(t.rows.back()[t.column("p_wheel_x")]) < 1e-6); // and gave it back: 9.7e-8
    CHECK(largest_L < 3e-15); // the motors' torques are internal: observed 3.1e-16
}

TEST_CASE("initial takes a wheel's rate relative to the body instead of its momentum",
          "[wheels][torque]") {
    // p = J (a . omega0 + wheel_dot): J = 0.1, a = (1, 0.2, 0) / |a|, omega0 from the rates
    const csv_table t = run_scene(
        "torque_wheels_rate",
        torque_model + "form: body\ninitial: {phi: 0.3, theta: 1.0, psi: 0.2, phi_dot: 0.5, "
                       "theta_dot: -0.4, psi_dot: 0.9, w1_dot: 7, p_w2: -0.5, w3_dot: -2}\ntime: "
                       "{start: 0, end: 1, samples: 3}\nrecord: [omega1, omega2, omega3, w1_dot, "
                       "w3_dot, p_w1, p_w2]\n");
    const auto& r0 = t.rows.front();
    CHECK(r0[t.column("w1_dot")] == Approx(7).margin(1e-13));
    CHECK(r0[t.column("w3_dot")] == Approx(-2).margin(1e-13));
    CHECK(r0[t.column("p_w2")] == Approx(-0.5).margin(1e-15));
    const double a = std::sqrt(1.04);
    const double w = (r0[t.column("omega1")] + 0.2 * r0[t.column("omega2")]) / a;
    CHECK(r0[t.column("p_w1")] == Approx(0.1 * (w + 7)).margin(1e-14));
    // and for a free wheel
    const csv_table f = run_scene(
        "free_wheel_rate",
        "model:\n  name: free_rate\n  parameters: {A: 2.0, B: 3.0, C: 4.0, Jw: 0.2}\n  inertia: "
        "[A, B, C]\n  wheels:\n    - {name: wheel, axis: [0, 0, 1], inertia: Jw}\ninitial: {phi: "
        "0.3, theta: 1.0, psi: 0.2, omega1: 0.5, omega2: -0.4, omega3: 0.9, wheel_dot: 3}\n"
        "time: {start: 0, end: 1, samples: 3}\nrecord: [wheel_dot, p_wheel]\n");
    CHECK(f.rows.front()[f.column("p_wheel")] == Approx(0.2 * (0.9 + 3)).margin(1e-15));
    CHECK(f.rows.front()[f.column("wheel_dot")] == Approx(3).margin(1e-14));
}

TEST_CASE("torque-driven wheels: what is refused is one located line, exit 2", "[wheels][torque]") {
    const auto refused = [](const std::string& text, const std::string& where,
                            const std::string& what) {
        const scratch_file scene("torque_wheels_bad.yaml", text);
        const std::string out = scene.path + ".csv";
        std::filesystem::remove(out);
        const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + out + "'");
        INFO(r.out << r.err);
        CHECK(r.status == 2);
        CHECK_FALSE(std::filesystem::exists(out)); // nothing written
        CHECK(r.err.find(where) != std::string::npos);
        CHECK(r.err.find(what) != std::string::npos);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    };
    const std::string initial = "initial: {phi: 0.3, theta: 1.0, psi: 0.2, omega1: 0.5, omega2: "
                                "-0.4, omega3: 0.9";
    const std::string time = "time: {start: 0, end: 1, samples: 3}\n";
    refused(torque_model + "form: reduced\n" + initial + "}\n" + time,
            "torque_wheels_bad.yaml:6:67: ",
            "wheel 'w1' has a torque drive, which the reduced form does not take (its momentum "
            "p_w1 is a state of the run); use the lagrangian, hamiltonian or body form");
    refused(torque_model + initial + "}\n" + time + "integrator: {method: split4, step: 0.01}\n",
            "torque_wheels_bad.yaml:", "carries wheels");
    refused(torque_model + initial + ", p_w1: 1, w1_dot: 2}\n" + time,
            "torque_wheels_bad.yaml:9:100: ",
            "give the wheel's momentum 'p_w1' or its rate 'w1_dot', not both");
    // a rate whose momentum J (a . omega + rate) overflows
    refused(torque_model + "parameters: {Jw: 10}\n" + initial + ", w1_dot: 1.7e308}\n" + time,
            "torque_wheels_bad.yaml:10:91: ", "the wheel's momentum from 'w1_dot' is not finite");
    refused(torque_model + "parameters: {p_w1: 1}\n" + initial + ", p_w1: 2}\n" + time,
            "torque_wheels_bad.yaml:10:89: ", "'p_w1' is given in both 'parameters' and 'initial'");
}

TEST_CASE("torque-driven wheels: sensitivities against central differences of the run",
          "[wheels][torque][sensitivities]") {
    // d(omega1)/d(k) and d(p_w1)/d(p_w1 at t0) at t = 2 against runs with k and p_w1 moved by
    // +-1e-4 (a scene's `parameters` on a model with wheels: the override is checked without
    // the wheels' own parameters)
    const std::string start = "initial: {phi: 0.3, theta: 1.0, psi: 0.2, omega1: 0.5, omega2: "
                              "-0.4, omega3: 0.9, p_w2: -0.5, p_w3: 0.8";
    const std::string rest = "time: {start: 0, end: 2, samples: 3}\nintegrator: {method: dop853, "
                             "rtol: 1e-12, atol: 1e-12}\nrecord: [omega1, p_w1]\n";
    const csv_table s =
        run_scene("torque_wheels_sens", torque_model + "form: body\n" + start + ", p_w1: 0.3}\n" +
                                            rest + "sensitivities: [parameters.k]\n");
    const auto at_end = [&](const std::string& k, const std::string& p, const char* column) {
        const csv_table t =
            run_scene("torque_wheels_fd", torque_model + "form: body\nparameters: {k: " + k +
                                              "}\n" + start + ", p_w1: " + p + "}\n" + rest);
        return t.rows.back()[t.column(column)];
    };
    const double dk =
        (at_end("0.3001", "0.3", "omega1") - at_end("0.2999", "0.3", "omega1")) / 2e-4;
    const double dp = (at_end("0.3", "0.3001", "p_w1") - at_end("0.3", "0.2999", "p_w1")) / 2e-4;
    const auto& last = s.rows.back();
    CHECK(std::abs(last[s.column("d(omega1)/d(parameters.k)")]) > 0.01); // observed -0.115
    // observed 2.3e-10 apart (the differences' own error)
    CHECK(last[s.column("d(omega1)/d(parameters.k)")] == Approx(dk).margin(3e-9));
    const csv_table p =
        run_scene("torque_wheels_sens_p", torque_model + "form: body\n" + start + ", p_w1: 0.3}\n" +
                                              rest + "sensitivities: [parameters.p_w1]\n");
    CHECK(p.rows.front()[p.column("d(p_w1)/d(parameters.p_w1)")] == 1);
    CHECK(p.rows.back()[p.column("d(p_w1)/d(parameters.p_w1)")] ==
          Approx(dp).margin(2e-10)); // observed 1.9e-11 apart (0.885)
}
