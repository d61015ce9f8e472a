// `initial:` attitude and angular velocity in every form (issue 28): a quaternion, the matrix A of
// (5.25) or the angles, with body omega, space omega or rates, start the same motion (checked
// against A and omega_body = A omega_space computed here); bad input is one located line, exit 2,
// nothing written; a start on the singular set of z-y-x angles starts in the body form.
#include "support.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>

using namespace rotgen::test;

namespace {

using mat = std::array<std::array<double, 3>, 3>;

// q = (0.9, 0.3, -0.2, 0.25)/|.| and its passive A = R(q)^T, R(q) the active rotation body ->
// space: R = [[1-2(y^2+z^2), 2(xy-wz), 2(xz+wy)], [2(xy+wz), 1-2(x^2+z^2), 2(yz-wx)], [2(xz-wy),
// 2(yz+wx), 1-2(x^2+y^2)]].
const double w = 0.89887710499006024, x = 0.29962570166335339, y = -0.19975046777556893,
             z = 0.24968808471946116;
const mat A{{{1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)},
             {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)},
             {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)}}};

std::string number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

std::string matrix_text() {
    std::string s = "A: [";
    for (int i = 0; i < 3; ++i)
        s += std::string(i ? ", " : "") + "[" + number(A[i][0]) + ", " + number(A[i][1]) + ", " +
             number(A[i][2]) + "]";
    return s + "]";
}

const std::string model = "{name: sat, angles: {sequence: zyx, names: [yaw, pitch, roll]}, "
                          "parameters: {n: 1}, inertia: [1.2, 1.0, 0.4], potential: "
                          "'3/2*n^2*(1.2*sin(pitch)^2 + sin(roll)^2*cos(pitch)^2 + "
                          "0.4*cos(roll)^2*cos(pitch)^2)'}";

// A heavy top in the same angles: its body form is free of the chart (gravity's torque is closed).
const std::string top = "{name: top, angles: {sequence: zyx, names: [yaw, pitch, roll]}, "
                        "inertia: [1, 1, 0.5], gravity: {mass: 1, g: 9.81, com: [0, 0, 0.1]}}";

std::string scene_text(const std::string& initial, const std::string& form = "lagrangian",
                       const std::string& body = model) {
    return "model: " + body + "\nform: " + form + "\ninitial: {" + initial +
           "}\ntime: {start: 0, end: 5, samples: 11}\n"
           "integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}\n"
           "record: [q0, q1, q2, q3, omega1, omega2, omega3, yaw, pitch, roll]\n";
}

struct outcome {
    run_result r;
    csv_table t;
    bool written = false;
};

outcome simulate(const std::string& name, const std::string& text) {
    const scratch_file scene(name + ".yaml", text);
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/" + name + ".csv";
    std::remove(csv.c_str());
    outcome o;
    o.r = run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'");
    o.written = std::ifstream(csv).good();
    if (o.written) o.t = read_csv(csv);
    std::remove(csv.c_str());
    return o;
}

double row_difference(const csv_table& a, const csv_table& b, const std::vector<std::string>& c) {
    double worst = 0;
    for (const auto& name : c) {
        const auto u = a.values(name), v = b.values(name);
        for (std::size_t i = 0; i < u.size(); ++i)
            worst = std::max(worst, std::abs(u[i] - v[i]));
    }
    return worst;
}

} // namespace

TEST_CASE("a quaternion, the matrix A and space omega start the same motion", "[angles]") {
    const std::array<double, 3> ws{0.4, -0.3, 2.0}; // space omega
    std::array<double, 3> wb{};                     // body omega = A omega_space
    for (int i = 0; i < 3; ++i)
        wb[i] = A[i][0] * ws[0] + A[i][1] * ws[1] + A[i][2] * ws[2];
    const std::string q =
        "q0: " + number(w) + ", q1: " + number(x) + ", q2: " + number(y) + ", q3: " + number(z);
    const std::string space =
        "omega_x: " + number(ws[0]) + ", omega_y: " + number(ws[1]) + ", omega_z: " + number(ws[2]);
    const std::string body =
        "omega1: " + number(wb[0]) + ", omega2: " + number(wb[1]) + ", omega3: " + number(wb[2]);
    const outcome by_q = simulate("attitude_q", scene_text(q + ", " + body));
    const outcome by_a = simulate("attitude_a", scene_text(matrix_text() + ", " + space));
    INFO(by_q.r.err << by_a.r.err);
    REQUIRE(by_q.r.status == 0);
    REQUIRE(by_a.r.status == 0);
    // the first row is the attitude and omega given (q0 >= 0: q and -q are one attitude)
    const auto& r0 = by_a.t.rows.front();
    const double q_given[4] = {w, x, y, z};
    double start = 0;
    for (int k = 0; k < 4; ++k)
        start = std::max(start, std::abs(r0[by_a.t.column("q" + std::to_string(k))] - q_given[k]));
    for (int i = 0; i < 3; ++i)
        start =
            std::max(start, std::abs(r0[by_a.t.column("omega" + std::to_string(i + 1))] - wb[i]));
    CHECK(start <= 2e-15); // observed 2.2e-16
    const double along =
        row_difference(by_q.t, by_a.t, {"q0", "q1", "q2", "q3", "omega1", "omega2", "omega3"});
    CHECK(along <= 2e-14); // observed 1.8e-15
    // and the angles it recorded are those of A: yaw, pitch, roll of R = Rz Ry Rx,
    // R20 = -sin(pitch), R10 / R00 = tan(yaw), R21 / R22 = tan(roll)
    const double pitch = std::asin(-A[0][2]), yaw = std::atan2(A[0][1], A[0][0]),
                 roll = std::atan2(A[1][2], A[2][2]);
    CHECK(std::abs(r0[by_a.t.column("yaw")] - yaw) <= 1e-15);
    CHECK(std::abs(r0[by_a.t.column("pitch")] - pitch) <= 1e-15);
    CHECK(std::abs(r0[by_a.t.column("roll")] - roll) <= 1e-15);
}

TEST_CASE("bad attitude input is one located line with exit 2 and nothing written", "[angles]") {
    const std::string body = "omega1: 0, omega2: 0, omega3: 1";
    const std::vector<std::pair<std::string, std::string>> cases{
        {"q0: 1.01, q1: 0, q2: 0, q3: 0, " + body, "norm"},
        {"A: [[1, 0, 0], [0, 1, 0.001], [0, 0, 1]], " + body, "not a rotation"},
        {"A: [[1, 0, 0], [0, 1, 0], [0, 0, -1]], " + body, "not a rotation"},
        {"q0: 1, q1: 0, q2: 0, q3: 0, p_yaw: 0, p_pitch: 0, p_roll: 1", "momenta need"},
        {"q0: 1, q1: 0, q2: 0, q3: 0, yaw: 0, pitch: 0, roll: 0, " + body, "one way only"},
        {"q0: 1, q1: 0, q2: 0, q3: 0, omega1: 0, omega2: 0, omega_z: 1", "one way only"},
        {"q0: 1, q1: 0, q2: 0, " + body, "missing q3"},
        {"yaw: 0, pitch: 2, roll: 0, " + body, "outside [-pi/2, pi/2]"}};
    for (const auto& [initial, why] : cases) {
        const outcome o = simulate("attitude_bad", scene_text(initial));
        INFO(initial << "\n" << o.r.err);
        CHECK(o.r.status == 2);
        CHECK_FALSE(o.written);
        CHECK(text_lines(o.r.err).size() == 1);
        CHECK(o.r.err.find("attitude_bad.yaml:3:") != std::string::npos);
        CHECK(o.r.err.find(why) != std::string::npos);
    }
}

TEST_CASE("a heavy top started on the zyx singular set starts in the body form and runs as it",
          "[angles]") {
    // pitch = pi/2 exactly: A = Ax(roll) Ay(pi/2) Az(yaw) with yaw = 0.3, roll = 0 has
    // q = qz(0.3) (x) qy(pi/2): (c c, -s s, c s, s c) with c, s of 0.15 and of pi/4
    const double h = std::sqrt(0.5), c = std::cos(0.15), s = std::sin(0.15);
    const std::string q = "q0: " + number(c * h) + ", q1: " + number(-s * h) +
                          ", q2: " + number(c * h) + ", q3: " + number(s * h);
    const std::string body = "omega1: 0.3, omega2: -0.2, omega3: 1.5";
    const outcome euler = simulate("attitude_pole", scene_text(q + ", " + body, "lagrangian", top));
    const outcome plain = simulate("attitude_pole_body", scene_text(q + ", " + body, "body", top));
    INFO(euler.r.err << plain.r.err);
    REQUIRE(euler.r.status == 0);
    REQUIRE(plain.r.status == 0);
    CHECK((euler.r.out + euler.r.err).find("started in the body form (initial |cos pitch|") !=
          std::string::npos);
    CHECK(std::abs(euler.t.rows.front()[euler.t.column("pitch")] - 1.5707963267948966) <= 1e-8);
    const double d =
        row_difference(euler.t, plain.t, {"q0", "q1", "q2", "q3", "omega1", "omega2", "omega3"});
    CHECK(d <= 3e-11); // observed 3.1e-12
}
