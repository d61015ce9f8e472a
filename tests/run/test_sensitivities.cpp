// Sensitivities integrated with the motion (scene key `sensitivities:`, run/sensitivity_run.hpp),
// against independent truth: central differences of whole runs (members of a prepared scene with
// the key's value moved by +-h, sweep's meaning), the closed form of the free symmetric top, and
// the symplecticity of the Hamiltonian flow's state-transition matrix.
#include "support.hpp"

#include "run/engine.hpp"
#include "run/prepared.hpp"
#include "scene/scene.hpp"
#include "support/format.hpp"
#include "sweep/outcome.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

using namespace rotgen;

namespace {

scene_spec scene_of(const std::string& name, const std::string& text) {
    const test::scratch_file f("sens_" + name + ".yaml", text);
    return load_scene(f.path);
}

rotgen::run_result run_values(const scene_spec& scene, const member_values& v) {
    stage_timings timings;
    const prepared_scene prepared(scene, timings);
    return run_member(prepared, v, timings);
}

// The member's value a key sets.
double& value_of(member_values& v, const value_key& k) {
    if (k.target == value_key::angle) return v.angles[k.index];
    if (k.target == value_key::rate) return v.initial_rates[k.index];
    return v.parameters[k.index];
}

// Every d(column)/d(key) of the run against central differences of runs at rtol 1e-13, atol
// 1e-15 (the method's own tolerance when `fd_tolerance` is false) with the key moved by +-h and
// +-h/2, h = 1e-3 max(|value|, 0.1), extrapolated (Richardson: (4 D(h/2) - D(h)) / 3, error
// O(h^4)): a plain central difference at h = 1e-4 left 1.5e-5 of truncation on the heavy top's h,
// and one at 1e-5 left the runs' rounding, 1e-14 / 1e-6, on columns whose derivative is 0 (Lz by
// cz). Angle columns are differenced modulo 2 pi (the body form's wrap into [0, 2 pi)). Returns
// the largest error relative to max(|d|, 1e-3).
double worst_against_differences(const scene_spec& scene, bool fd_tolerance = true,
                                 double tolerance = 1e-6) {
    const rotgen::run_result r = run_values(scene, values_of(scene));
    REQUIRE(r.ok);
    const std::size_t k = scene.sensitivities.keys.size(), columns = r.columns.size();
    REQUIRE(r.sensitivity_keys.size() == k);
    REQUIRE(r.sensitivity_rows.size() == r.rows.size());
    scene_spec plain = scene;
    plain.sensitivities = {};
    if (fd_tolerance) plain.integrator.rtol = 1e-13, plain.integrator.atol = 1e-15;
    stage_timings timings;
    const prepared_scene prepared(plain, timings);
    const member_values values = values_of(scene);
    double worst = 0;
    for (std::size_t j = 0; j < k; ++j) {
        member_values base = values;
        const double x = value_of(base, scene.sensitivities.keys[j]);
        const double h = 1e-3 * std::max(std::abs(x), 0.1);
        const auto at = [&](double v) {
            member_values m = values;
            value_of(m, scene.sensitivities.keys[j]) = v;
            return run_member(prepared, m, timings);
        };
        const rotgen::run_result a = at(x + h), b = at(x - h), a2 = at(x + h / 2),
                                 b2 = at(x - h / 2);
        std::size_t checked = 0;
        const auto& angles = scene.model.angles.names;
        for (std::size_t c = 0; c < columns; ++c) {
            const bool angle =
                std::find(angles.begin(), angles.end(), r.columns[c]) != angles.end();
            const auto diff = [&](const rotgen::run_result& p, const rotgen::run_result& m,
                                  std::size_t s) {
                const double d = p.rows[s][c + 1] - m.rows[s][c + 1];
                return angle ? std::remainder(d, 2 * 3.14159265358979323846) : d;
            };
            const std::string name = "d(" + r.columns[c] + ")/d(" + r.sensitivity_keys[j] + ")";
            const auto at =
                std::find(r.sensitivity_columns.begin(), r.sensitivity_columns.end(), name);
            if (at == r.sensitivity_columns.end()) continue;
            const auto m = static_cast<std::size_t>(at - r.sensitivity_columns.begin());
            ++checked;
            for (std::size_t s = 0; s < r.rows.size(); ++s) {
                const double fd1 = diff(a, b, s) / (2 * h), fd2 = diff(a2, b2, s) / h,
                             fd = (4 * fd2 - fd1) / 3;
                const double d = r.sensitivity_rows[s][m];
                const double e = std::abs(d - fd) / std::max(std::abs(d), 1e-3);
                INFO(name << " at t = " << r.rows[s][0] << ": " << d << " vs " << fd);
                CHECK(e < tolerance);
                worst = std::max(worst, e);
            }
        }
        CHECK(checked == columns);
    }
    return worst;
}

const std::string heavy_top = "model: " + test::model_path("heavy_top") + R"(
form: lagrangian
initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0.3, theta_dot: 0.1, psi_dot: 5}
time: {start: 0, end: 5, samples: 11}
integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}
record: [theta, phi, theta_dot, psi_dot, energy, p_psi]
switch_chart: false
sensitivities: [initial.theta, initial.psi_dot, parameters.h, parameters.I3]
)";

} // namespace

TEST_CASE("sensitivities of the heavy top agree with central differences of whole runs",
          "[sensitivities]") {
    const double worst = worst_against_differences(scene_of("heavy", heavy_top));
    CHECK(worst < 3e-7); // observed 3.1e-8
}

TEST_CASE("sensitivities of the full-tensor top from body omega agree with central differences",
          "[sensitivities]") {
    const double worst = worst_against_differences(
        scene_of("tensor", "model: " + test::model_path("full_tensor_top") +
                               R"(
form: lagrangian
initial: {phi: 0.2, theta: 0.8, psi: -0.4, omega1: 0.5, omega2: -0.3, omega3: 4}
time: {start: 0, end: 3, samples: 7}
integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}
record: [theta, psi, omega1, omega3, energy, Lz]
switch_chart: false
sensitivities: [initial.psi, initial.omega1, parameters.Ixy, parameters.cz, parameters.Izz]
)"));
    CHECK(worst < 1e-6); // observed 8.2e-7
}

TEST_CASE("sensitivities of the z-y-x satellite from momenta in the Hamiltonian form agree with "
          "central differences",
          "[sensitivities]") {
    const double worst = worst_against_differences(
        scene_of("satellite", "model: " + test::model_path("satellite_zyx") +
                                  R"(
form: hamiltonian
initial: {yaw: 0.1, pitch: 0.3, roll: -0.2, p_yaw: 0.4, p_pitch: 0.1, p_roll: -0.2}
time: {start: 0, end: 6, samples: 7}
integrator: {method: dopri5, rtol: 1e-12, atol: 1e-14}
record: [yaw, pitch, roll, p_pitch, energy, q0, q1, q2, q3]
switch_chart: false
sensitivities: [initial.pitch, initial.p_roll, parameters.I2, parameters.n]
)"));
    CHECK(worst < 1e-8); // observed 3.3e-9 (1.3e-9 without q0..q3)
}

TEST_CASE("sensitivities of rk4 are the derivatives of its discrete map", "[sensitivities]") {
    std::string text = heavy_top;
    text.replace(text.find("integrator:"), text.find("record:") - text.find("integrator:"),
                 "integrator: {method: rk4, step: 0.01}\n");
    // the differences of runs at the same step differentiate the same map
    const double worst = worst_against_differences(scene_of("rk4", text), false);
    CHECK(worst < 5e-7); // observed 7.8e-8
}

TEST_CASE("sensitivities without error control follow the state's steps and still agree",
          "[sensitivities]") {
    std::string text = heavy_top;
    text.replace(text.find("sensitivities:"), std::string::npos,
                 "sensitivities: {keys: [initial.theta, parameters.h], error_control: false}\n");
    const scene_spec with = scene_of("errcon", text);
    const double worst = worst_against_differences(with, true, 1e-6);
    CHECK(worst < 3e-7); // observed 3.1e-8
    scene_spec plain = with;
    plain.sensitivities = {};
    const rotgen::run_result a = run_values(with, values_of(with)),
                             b = run_values(plain, values_of(plain));
    CHECK(a.stats.accepted == b.stats.accepted); // S is not in the error norm
    scene_spec controlled = with;
    controlled.sensitivities.error_control = true;
    CHECK(run_values(controlled, values_of(controlled)).stats.accepted > b.stats.accepted);
}

// The free symmetric top (inertia [I1, I1, I3]): omega3 constant, omega1 + i omega2 =
// w0 exp(i Omega t), Omega = (I3 - I1) omega3 / I1 (Euler's equations, 5.87-5.89), differentiated
// by hand: d w/d s = w0 i t (dOmega/ds) exp(i Omega t), dOmega/d omega3 = (I3 - I1)/I1,
// dOmega/d I1 = -I3 omega3/I1^2, dOmega/d I3 = omega3/I1.
// DOP853 integrates the variational equations, Taylor the recurrences of (y, S).
TEST_CASE("sensitivities of the free symmetric top are its closed form's derivatives",
          "[sensitivities]") {
    const auto [method, bound] =
        GENERATE(table<std::string, double>({{"dop853", 1e-11}, {"taylor", 1.5e-12}}));
    INFO(method);
    const scene_spec scene = scene_of("symmetric_" + method, R"(
model: {name: symmetric, parameters: {I1: 1.3, I3: 0.6}, inertia: [I1, I1, I3]}
form: body
initial: {phi: 0, theta: 0.5, psi: 0, omega1: 0.7, omega2: -0.2, omega3: 3}
time: {start: 0, end: 20, samples: 201}
integrator: {method: )" + method + R"(, rtol: 1e-12, atol: 1e-14}
record: [omega1, omega2, omega3]
sensitivities: [initial.omega3, parameters.I1, parameters.I3]
)");
    const rotgen::run_result r = run_values(scene, values_of(scene));
    REQUIRE(r.ok);
    REQUIRE(r.sensitivity_columns.size() == 9);
    const double I1 = 1.3, I3 = 0.6, w3 = 3, Omega = (I3 - I1) * w3 / I1;
    const std::complex<double> w0(0.7, -0.2), i(0, 1);
    const double dOmega[3] = {(I3 - I1) / I1, -I3 * w3 / (I1 * I1), w3 / I1};
    double worst = 0;
    for (std::size_t s = 0; s < r.rows.size(); ++s) {
        const double t = r.rows[s][0];
        for (std::size_t j = 0; j < 3; ++j) {
            const std::complex<double> dw = w0 * i * t * dOmega[j] * std::exp(i * Omega * t);
            const double exact[3] = {dw.real(), dw.imag(), j == 0 ? 1.0 : 0.0};
            for (std::size_t c = 0; c < 3; ++c) // d(omega_c)/d(key_j): record order, key order
                worst = std::max(worst, std::abs(r.sensitivity_rows[s][c * 3 + j] - exact[c]));
        }
    }
    CHECK(worst < bound); // observed 1.2e-12 (dop853), 1.4e-13 (taylor)
}

// For a conservative model in the Hamiltonian form, Phi = dy(t)/dy(t0) is symplectic:
// Phi^T J Phi = J, J = [[0, I], [-I, 0]] in (q, p).
TEST_CASE("the heavy top's state-transition matrix in the Hamiltonian form is symplectic",
          "[sensitivities]") {
    const scene_spec scene = scene_of("symplectic", "model: " + test::model_path("heavy_top") + R"(
form: hamiltonian
initial: {phi: 0, theta: 0.7, psi: 0, phi_dot: 0.4, theta_dot: 0.2, psi_dot: 6}
time: {start: 0, end: 100, samples: 11}
integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}
switch_chart: false
sensitivities: {keys: all_initial}
)");
    const rotgen::run_result r = run_values(scene, values_of(scene));
    REQUIRE(r.ok);
    REQUIRE(r.sensitivity_keys.size() == 6);
    CHECK(r.sensitivity_keys[0] == "y0.phi");
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, 6);
    J.topRightCorner(3, 3) = Eigen::Matrix3d::Identity();
    J.bottomLeftCorner(3, 3) = -Eigen::Matrix3d::Identity();
    double worst = 0, largest = 0;
    for (const auto& flat : r.state_sensitivities) {
        const Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>> Phi(flat.data());
        const double norm = Phi.norm();
        largest = std::max(largest, norm);
        worst =
            std::max(worst, (Phi.transpose() * J * Phi - J).norm() / std::max(1.0, norm * norm));
    }
    CHECK(largest > 20); // observed 209: the flow shears, Phi is far from the identity
    CHECK(worst < 1e-8); // observed 8.4e-15 (the issue's bound)
}

TEST_CASE("sensitivities refuse bad keys, other methods and the chart switch, located",
          "[sensitivities]") {
    const auto refused = [](const std::string& name, std::string text, const std::string& from,
                            const std::string& to) {
        text.replace(text.find(from), from.size(), to);
        const test::scratch_file f("sens_refused_" + name + ".yaml", text);
        const test::run_result r = test::run_rotgen("simulate '" + f.path + "' -o /dev/null");
        CHECK(r.status == 2);
        return r.err;
    };
    CHECK_THAT(refused("key", heavy_top, "initial.theta,", "initial.thet,"),
               Catch::Contains(":8:17: unknown sensitivity key 'initial.thet' for this scene; "
                               "did you mean 'initial.theta'?"));
    CHECK_THAT(refused("method", heavy_top, "method: dop853, rtol: 1e-12, atol: 1e-14",
                       "method: implicit_midpoint, step: 0.01"),
               Catch::Contains(":8:16: integrator implicit_midpoint does not integrate "
                               "sensitivities; use dop853, dopri5, rk4 or taylor"));
    std::string low = heavy_top;
    low.replace(low.find("theta: 0.5"), 10, "theta: 0.12");
    low.replace(low.find("theta_dot: 0.1"), 14, "theta_dot: -0.3");
    CHECK_THAT(refused("switch", low, "switch_chart: false", "switch_chart: true"),
               Catch::Contains(":8:16: sensitivities are not carried across the chart switch "
                               "this run makes at t = 0.5"));
    // an action would make S jump (S+ = h_y S- + ...), which is not built: refused at the key
    CHECK_THAT(refused("action", heavy_top, "switch_chart: false",
                       "switch_chart: false\nevents:\n  - {name: kick, when: t - 1, action: "
                       "{impulse: [0.1, 0, 0]}}"),
               Catch::Contains(":10:16: sensitivities are not carried across an event's action "
                               "(event 'kick' at line 9 acts); run them without the action"));
}

// The body form starts from the angles' quaternion: S(t0) of qw..qz is its derivative by the
// angles (the product rule on q_z(phi) (x) q_x(theta) (x) q_z(psi)); gravity carries it into omega.
TEST_CASE("sensitivities of the heavy top in the body form by the initial angles agree with "
          "central differences",
          "[sensitivities]") {
    const double worst =
        worst_against_differences(scene_of("body", "model: " + test::model_path("heavy_top") +
                                                       R"(
form: body
initial: {phi: 0.3, theta: 0.9, psi: -0.5, omega1: 0.4, omega2: -0.2, omega3: 5}
time: {start: 0, end: 4, samples: 9}
integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}
record: [omega1, omega2, omega3, energy, Lz]
sensitivities: [initial.phi, initial.theta, initial.psi, initial.omega2, parameters.M]
)"));
    CHECK(worst < 3e-7); // observed 3.9e-8
}

// The Euler-angle forms record the attitude q0..q3 from the angles, q = q_z(phi) (x) q_x(theta)
// (x) q_z(psi) with q0 >= 0: its d(...) columns are that map's derivative (through the sign)
// times S. body_z (row 3 of A, from the record program) is checked beside it.
TEST_CASE("sensitivities of the attitude quaternion in the lagrangian form agree with central "
          "differences",
          "[sensitivities]") {
    std::string text = heavy_top;
    text.replace(text.find("record:"), text.find("switch_chart:") - text.find("record:"),
                 "record: [q0, q1, q2, q3, theta, body_z]\n");
    text.replace(text.find("sensitivities:"), std::string::npos,
                 "sensitivities: [initial.phi, initial.theta, initial.psi_dot, parameters.h]\n");
    const double worst = worst_against_differences(scene_of("lagrangian_q", text));
    CHECK(worst < 3e-9); // observed 1.1e-9
}

// The body form recovers the angles from its quaternion, their rates q_dot = J^-1 omega and the
// momenta p = J^T I omega at each sample: their d(...) columns are the chain rule through that
// recovery (its wrap into [0, 2 pi) and its branches included), with I's parameters in p. In z-x-z
// (the heavy top) and in a Tait-Bryan sequence (the z-y-x satellite: the runtime's general angle
// recovery and J^-1).
TEST_CASE("sensitivities of the body form's angles, rates, momenta and attitude agree with "
          "central differences",
          "[sensitivities]") {
    using row = std::tuple<std::string, std::string, std::string, double>;
    const auto [model, initial, record,
                bound] = GENERATE(table<std::string, std::string, std::string, double>({
        row{"heavy_top", "{phi: 0.3, theta: 0.9, psi: -0.5, omega1: 0.4, omega2: -0.2, omega3: 5}",
            "[phi, theta, psi, phi_dot, theta_dot, psi_dot, p_phi, p_theta, p_psi, q0, q1, q2, "
            "q3, body_x]\nsensitivities: [initial.phi, initial.theta, initial.omega2, "
            "parameters.M, "
            "parameters.I1]",
            2e-7}, // observed 2.2e-8
        row{"satellite_zyx",
            "{yaw: 0.1, pitch: 0.3, roll: -0.2, omega1: 0.4, omega2: 0.1, omega3: -0.2}",
            "[yaw, pitch, roll, yaw_dot, pitch_dot, roll_dot, p_yaw, p_pitch, p_roll, q0, q1, q2, "
            "q3]\nsensitivities: [initial.pitch, initial.omega1, parameters.I2, parameters.n]",
            1e-8}, // observed 1.0e-9
    }));
    const double worst = worst_against_differences(scene_of(
        "body_" + model, "model: " + test::model_path(model) + "\nform: body\ninitial: " + initial +
                             "\ntime: {start: 0, end: 4, samples: 9}\nintegrator: "
                             "{method: dop853, rtol: 1e-12, atol: 1e-14}\nrecord: " +
                             record + "\n"));
    INFO(model);
    CHECK(worst < bound);
}

// d(t_event)/d(key) = -(g_y S + g_s)/(g_t + g_y f), against Richardson-extrapolated central
// differences of the event times (h = 1e-3 max(|value|, 0.1)) of runs at rtol 1e-13.
TEST_CASE("the sensitivities of event times agree with central differences", "[sensitivities]") {
    std::string text = heavy_top;
    text += "events: [{name: turn, when: theta_dot}]\n";
    const scene_spec scene = scene_of("events", text);
    const rotgen::run_result r = run_values(scene, values_of(scene));
    REQUIRE(r.event_rows.size() >= 3);
    const std::size_t k = scene.sensitivities.keys.size();
    REQUIRE(r.event_sensitivity_columns.size() == k * (1 + r.columns.size()));
    CHECK(r.event_sensitivity_columns[0] == "d(t_event)/d(initial.theta)");
    scene_spec plain = scene;
    plain.sensitivities = {};
    plain.integrator.rtol = 1e-13, plain.integrator.atol = 1e-15;
    stage_timings timings;
    const prepared_scene prepared(plain, timings);
    double worst = 0;
    for (std::size_t j = 0; j < k; ++j) {
        member_values base = values_of(scene);
        const double x = value_of(base, scene.sensitivities.keys[j]);
        const double h = 1e-3 * std::max(std::abs(x), 0.1);
        const auto times = [&](double v) {
            member_values m = base;
            value_of(m, scene.sensitivities.keys[j]) = v;
            const rotgen::run_result e = run_member(prepared, m, timings);
            REQUIRE(e.event_rows.size() == r.event_rows.size());
            std::vector<double> t;
            for (const auto& row : e.event_rows)
                t.push_back(row[0]);
            return t;
        };
        const std::vector<double> a = times(x + h), b = times(x - h), a2 = times(x + h / 2),
                                  b2 = times(x - h / 2);
        for (std::size_t e = 0; e < r.event_rows.size(); ++e) {
            const double fd = (4 * (a2[e] - b2[e]) / h - (a[e] - b[e]) / (2 * h)) / 3;
            const double d = r.event_sensitivity_rows[e][j];
            worst = std::max(worst, std::abs(d - fd) / std::max(std::abs(d), 1e-3));
        }
    }
    CHECK(worst < 5e-9); // observed 5e-10
}

// A sweep keeps the last row's derivatives: final.d(<column>)/d(<key>) in summary.csv, the same
// doubles as the member's own run.
TEST_CASE("a sweep's summary holds the final sensitivities of each member", "[sensitivities]") {
    const scene_spec scene = scene_of("sweep", heavy_top);
    member_values values = values_of(scene);
    values.parameters[4] = 0.2; // h
    const rotgen::run_result r = run_values(scene, values);
    stage_timings timings;
    prepared_scene prepared(scene, timings);
    prepared.keep_last_row_only();
    prepared.compile_all(timings);
    const summary_layout layout = layout_of(prepared);
    CHECK(layout.sensitivities == r.sensitivity_columns);
    const member_outcome o = run_one(prepared, layout, values, false);
    CHECK(o.final_sensitivities == r.sensitivity_rows.back());
    std::ostringstream header;
    write_summary_header(header, sweep_plan{}, layout);
    CHECK_THAT(header.str(), Catch::Contains(",final.p_psi,final.d(theta)/d(initial.theta),"));
    CHECK_THAT(summary_row_of(0, {}, layout, o),
               Catch::Contains(format_number(o.final_sensitivities.back()) + ","));
}
