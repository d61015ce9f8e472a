// `rotgen inspect MODEL.yaml --inertia` (text, LaTeX, JSON) and the stability report against
// simulations of the free body (rotgen simulate, body form).
#include "inertia/inertia.hpp"
#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

using namespace rotgen;
using namespace rotgen::test;

namespace {

bool contains(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}

std::string cube() {
    return "'" + model_path("cube_on_corner") + "'";
}

} // namespace

TEST_CASE("inertia: inspect --inertia: the cube on its corner as text", "[inertia][inspect]") {
    const run_result r = run_rotgen("inspect " + cube() + " --inertia");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(contains(
        r.out, "body: 1 part, total mass M, centre of mass (L/2, L/2, L/2), pivot (0, 0, 0)\n"));
    CHECK(contains(r.out, "  (2*L**2*M/3, -L**2*M/4, -L**2*M/4)\n")); // (5.43)
    CHECK(contains(r.out, "principal moments and axes (exact;"));
    CHECK(
        contains(r.out, "  I1 = L**2*M/6 = 0.00666667  along (sqrt(3)/3, sqrt(3)/3, sqrt(3)/3)\n"));
    CHECK(contains(r.out, "  I2 = 11*L**2*M/12 = 0.0366667  along "));
    CHECK(contains(r.out, "class: symmetric top"));
    CHECK(contains(
        r.out, "axis 1: stable: small deviations oscillate at Omega1 = 9/11 = 0.818182 (5.94)"));
    CHECK(contains(r.out, "axis 2: neutral"));
    CHECK(!contains(r.out, "kinetic energy"));                          // the report alone
    CHECK(run_rotgen("inspect " + cube() + " --inertia").out == r.out); // deterministic
}

TEST_CASE("inertia: inspect --inertia --format latex", "[inertia][inspect]") {
    const run_result r = run_rotgen("inspect " + cube() + " --inertia --format latex");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(contains(r.out, "\\begin{align*}\n"));
    CHECK(contains(r.out, "I &= \\begin{pmatrix} \\frac{2 L^{2} M}{3} & -\\frac{L^{2} M}{4}"));
    CHECK(contains(r.out,
                   "I_{1} &= \\frac{L^{2} M}{6}, & \\hat{e}_{1} &= \\left(\\frac{\\sqrt{3}}{3}"));
    CHECK(contains(r.out, "\\Omega_{1} &= \\frac{9}{11} \\, \\omega & &\\text{stable (5.94)}"));
    CHECK(contains(r.out, "\\end{align*}\n% class: symmetric top"));
}

TEST_CASE("inertia: inspect --inertia --format json adds 'inertia' and keeps every other key",
          "[inertia][inspect]") {
    const run_result plain = run_rotgen("inspect " + cube() + " --format json");
    const run_result r = run_rotgen("inspect " + cube() + " --inertia --format json");
    INFO(r.out << r.err);
    REQUIRE(plain.status == 0);
    REQUIRE(r.status == 0);
    // the normal object, byte for byte, up to its closing brace; then the new key
    REQUIRE(plain.out.size() > 3);
    const std::string body = plain.out.substr(0, plain.out.size() - 3); // without "\n}\n"
    CHECK(plain.out.substr(plain.out.size() - 3) == "\n}\n");
    CHECK(r.out.rfind(body + ",\n  \"inertia\": {\n", 0) == 0);
    CHECK(r.out.substr(r.out.size() - 7) == "\n  }\n}\n");
    const std::string inertia = r.out.substr(body.size());
    CHECK(contains(inertia, "\"tensor\": [[\"2*L**2*M/3\", \"-L**2*M/4\", \"-L**2*M/4\"], "));
    CHECK(contains(inertia,
                   "\"principal_moments\": [\"L**2*M/6\", \"11*L**2*M/12\", \"11*L**2*M/12\"]"));
    CHECK(
        contains(inertia, "\"principal_axes\": [[\"sqrt(3)/3\", \"sqrt(3)/3\", \"sqrt(3)/3\"], "));
    CHECK(contains(inertia, "\"class\": \"symmetric\""));
    CHECK(contains(
        inertia,
        "{\"axis\": 1, \"stable\": true, \"rate\": 0.8181818181818181, \"kind\": \"stable\", "
        "\"rate_expression\": \"9/11\"}"));
    CHECK(
        contains(inertia, "{\"axis\": 2, \"stable\": false, \"rate\": 0.0, \"kind\": \"neutral\""));
    CHECK(contains(inertia, "\"exact_moments\": true"));
    CHECK(contains(inertia, "\"centre_of_mass\": [\"L/2\", \"L/2\", \"L/2\"]"));
    CHECK(contains(inertia, "\"pivot\": [\"0\", \"0\", \"0\"]"));
    // a model given by its tensor: principal axes numeric, no body keys
    const run_result full =
        run_rotgen("inspect '" + model_path("full_tensor_top") + "' --inertia --format json");
    REQUIRE(full.status == 0);
    CHECK(contains(full.out, "\"exact_moments\": false"));
    CHECK(contains(full.out, "\"class\": \"asymmetric\""));
    CHECK(!contains(full.out, "\"centre_of_mass\""));
}

TEST_CASE("inertia: inspect --inertia prints fractions the same way in every run",
          "[inertia][inspect]") {
    // symbolic masses about the default pivot (the centre of mass): rational functions
    const scratch_file file(
        "inertia_fractions.yaml",
        "name: fractions\nparameters: {m1: 1, m2: 3, x1: 0.5, x2: -0.2, r: 0.1}\n"
        "body:\n  parts:\n    - point: {mass: m1, at: [x1, 0, 0]}\n"
        "    - sphere: {mass: m2, radius: r, at: [x2, 0, 0]}\n");
    const run_result first = run_rotgen("inspect '" + file.path + "' --inertia --format json");
    INFO(first.err);
    REQUIRE(first.status == 0);
    for (int i = 0; i < 4; ++i)
        CHECK(run_rotgen("inspect '" + file.path + "' --inertia --format json").out == first.out);
}

namespace {

// A box turned by Euler angles: principal axes off the body axes, moments 5, 10, 13 (exact).
const std::string box_model =
    "name: turned_box\n"
    "body:\n"
    "  parts:\n"
    "    - box: {mass: 12, size: [1, 2, 3], at: [0, 0, 0], rotation: [pi/6, pi/4, pi/3]}\n";

std::string indented(const std::string& text) {
    std::string out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
        out += "  " + line + "\n";
    return out;
}

std::string number(double x) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

// Spins the free box at rate 1 about principal axis k with a deviation eps along axis j (in
// body axes, from the report) and returns t and the deviation omega . e_j.
std::pair<std::vector<double>, std::vector<double>> deviation(const principal_axes& p, int k, int j,
                                                              double eps, double end, int samples,
                                                              const std::string& name) {
    double w[3];
    for (int i = 0; i < 3; ++i)
        w[i] = p.axis_values[k][i] + eps * p.axis_values[j][i];
    const scratch_file scene(
        name + ".yaml",
        "model:\n" + indented(box_model) +
            "form: body\ninitial: {phi: 0, theta: 1, psi: 0, omega1: " + number(w[0]) +
            ", omega2: " + number(w[1]) + ", omega3: " + number(w[2]) +
            "}\ntime: {end: " + number(end) + ", samples: " + std::to_string(samples) +
            "}\nintegrator: {method: dop853, rtol: 1e-12, atol: 1e-15}\n"
            "record: [omega1, omega2, omega3]\n");
    const std::string out = std::string(ROTGEN_BINARY_DIR) + "/" + name + ".csv";
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + out + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    const csv_table t = read_csv(out);
    std::remove(out.c_str());
    const auto w1 = t.values("omega1"), w2 = t.values("omega2"), w3 = t.values("omega3");
    std::vector<double> d;
    for (std::size_t i = 0; i < w1.size(); ++i)
        d.push_back(w1[i] * p.axis_values[j][0] + w2[i] * p.axis_values[j][1] +
                    w3[i] * p.axis_values[j][2]);
    return {t.values("t"), d};
}

} // namespace

TEST_CASE("inertia: the stability report agrees with simulations of the free body within 1 %",
          "[inertia][stability][simulate]") {
    const scratch_file model("inertia_turned_box.yaml", box_model);
    const model_spec spec = load_model(model.path);
    const inertia_report report = analyse_inertia(spec.inertia, spec.parameter_defaults());
    REQUIRE(report.principal.moment_values[0] == Approx(5));
    REQUIRE(report.principal.moment_values[1] == Approx(10));
    REQUIRE(report.principal.moment_values[2] == Approx(13));
    REQUIRE(report.stability[0].kind == stability_kind::stable);
    REQUIRE(report.stability[1].kind == stability_kind::unstable);
    REQUIRE(report.stability[2].kind == stability_kind::stable);
    const double pi = 3.141592653589793;

    for (int k : {0, 2}) {
        SECTION("stable axis " + std::to_string(k + 1) + ": the deviation oscillates at Omega") {
            // Deviation along the intermediate axis, the third component 0 at t = 0:
            // delta(t) = eps cos(Omega t). Frequency from the mean period of upward zero crossings.
            const double eps = 1e-6;
            const auto [t, d] = deviation(report.principal, k, 1, eps, 80, 8001,
                                          "inertia_stable" + std::to_string(k));
            std::vector<double> crossings;
            for (std::size_t i = 1; i < d.size(); ++i)
                if (d[i - 1] < 0 && d[i] >= 0)
                    crossings.push_back(t[i - 1] +
                                        (t[i] - t[i - 1]) * -d[i - 1] / (d[i] - d[i - 1]));
            REQUIRE(crossings.size() >= 4);
            const double period =
                (crossings.back() - crossings.front()) / double(crossings.size() - 1);
            CHECK(2 * pi / period == Approx(report.stability[k].rate_value).epsilon(0.01));
            CHECK(*std::max_element(d.begin(), d.end()) < 10 * eps); // it stays small
        }
    }
    SECTION("unstable axis 2: the deviation grows like cosh(Omega t)") {
        // With the third component 0 at t = 0 the linearised solution is eps cosh(Omega t); while
        // it is small (1e-5 .. 1e-3 of the spin) acosh(delta/eps)/t estimates Omega.
        const double eps = 1e-7;
        const auto [t, d] = deviation(report.principal, 1, 0, eps, 22, 2201, "inertia_unstable");
        double sum = 0;
        int n = 0;
        for (std::size_t i = 1; i < d.size(); ++i)
            if (std::abs(d[i]) > 1e-5 && std::abs(d[i]) < 1e-3) {
                sum += std::acosh(std::abs(d[i]) / eps) / t[i];
                ++n;
            }
        REQUIRE(n > 100);
        CHECK(sum / n == Approx(report.stability[1].rate_value).epsilon(0.01));
        CHECK(std::abs(d.back()) > 1e-3); // and it does grow
    }
}
