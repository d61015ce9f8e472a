// Issue 14: `inspect --inertia` of a body built from parts printed kilobyte-long stability
// expressions. They are now evaluated at the parameters' defaults; `--symbolic` keeps the
// expressions (with their values). Plain numbers (the cube's 9/11) are exact either way.
#include "error_sites.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

using namespace rotgen::test;

namespace {

// A box (m; a, b, c) centred at (0, 0, h) and a point M at (a, 0, 0), about the origin.
const std::string model =
    "name: parts_top\nparameters: {m: 1, M: 0.5, a: 0.3, b: 0.2, c: 0.1, "
    "h: 0.4}\nbody:\n  pivot: [0, 0, 0]\n  parts:\n    - box: {mass: m, "
    "size: [a, b, c], at: [0, 0, h]}\n    - point: {mass: M, at: [a, 0, 0]}\n";

std::string g6(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
}

// |Omega_i| per unit spin, by hand: the box's central moments m(b²+c²)/12, m(a²+c²)/12,
// m(a²+b²)/12 plus the parallel-axis terms m h² (x, y) and M a² (y, z); then
// s_i = (I_i − I_j)(I_i − I_k)/(I_j I_k) (inertia.hpp, from 5.94 and 5.100), rate sqrt|s_i|.
std::array<double, 3> rates() {
    const double m = 1, M = 0.5, a = 0.3, b = 0.2, c = 0.1, h = 0.4;
    const double I[3] = {m * (b * b + c * c) / 12 + m * h * h,
                         m * (a * a + c * c) / 12 + m * h * h + M * a * a,
                         m * (a * a + b * b) / 12 + M * a * a};
    std::array<double, 3> r{};
    for (int i = 0; i < 3; ++i) {
        const double Ij = I[(i + 1) % 3], Ik = I[(i + 2) % 3];
        r[i] = std::sqrt(std::abs((I[i] - Ij) * (I[i] - Ik) / (Ij * Ik)));
    }
    return r;
}

bool contains(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}

} // namespace

TEST_CASE("inspect: --inertia evaluates a body's stability rates, --symbolic keeps them",
          "[inspect][inertia]") {
    const scratch_file file("inspect_parts_top.yaml", model);
    const auto r = rates(); // 0.668714, 0.91915, 0.69799 (I2 the largest: axis 1 unstable)
    SECTION("text") {
        const run_result plain =
            run_rotgen("inspect inspect_parts_top.yaml --inertia", ROTGEN_BINARY_DIR);
        INFO(plain.out << plain.err);
        REQUIRE(plain.status == 0);
        CHECK(contains(plain.out, "numbers at the parameters' defaults; --symbolic shows their "
                                  "expressions):\n"));
        CHECK(contains(plain.out, "  axis 1: unstable: small deviations grow like exp(Omega1 t), "
                                  "Omega1 = " +
                                      g6(r[0]) + " (5.100)\n"));
        CHECK(contains(plain.out, "  axis 2: stable: small deviations oscillate at Omega2 = " +
                                      g6(r[1]) + " (5.94)\n"));
        CHECK(contains(plain.out, "  axis 3: stable: small deviations oscillate at Omega3 = " +
                                      g6(r[2]) + " (5.94)\n"));
        CHECK(!contains(plain.out, "sqrt("));
        CHECK(plain.out.size() < 1500); // 1100 bytes; 6735 with the expressions
        const run_result sym =
            run_rotgen("inspect inspect_parts_top.yaml --inertia --symbolic", ROTGEN_BINARY_DIR);
        REQUIRE(sym.status == 0);
        CHECK(contains(sym.out, "Omega1 = sqrt("));
        CHECK(contains(sym.out, ") = " + g6(r[0]) + " (5.100)\n"));
        CHECK(!contains(sym.out, "--symbolic shows"));
        CHECK(sym.out.size() > 5000);
    }
    SECTION("LaTeX") {
        const run_result plain = run_rotgen(
            "inspect inspect_parts_top.yaml --inertia --format latex", ROTGEN_BINARY_DIR);
        REQUIRE(plain.status == 0);
        CHECK(contains(plain.out, "\\Omega_{2} &= " + g6(r[1]) +
                                      " \\, \\omega & &\\text{stable "
                                      "(5.94)}"));
        const run_result sym =
            run_rotgen("inspect inspect_parts_top.yaml --inertia --symbolic --format latex",
                       ROTGEN_BINARY_DIR);
        REQUIRE(sym.status == 0);
        CHECK(contains(sym.out, "\\Omega_{2} &= \\sqrt{"));
    }
    SECTION("an exact number is shown exactly either way") {
        const std::string cube = "inspect '" + model_path("cube_on_corner") + "' --inertia";
        const std::string line =
            "axis 1: stable: small deviations oscillate at Omega1 = 9/11 = 0.818182 (5.94)";
        CHECK(contains(run_rotgen(cube).out, line));
        CHECK(contains(run_rotgen(cube + " --symbolic").out, line));
    }
}

TEST_CASE("inspect: --symbolic without --inertia is a usage error", "[inspect][errors]") {
    check_error_line(run_rotgen("inspect '" + model_path("heavy_top") + "' --symbolic"),
                     "rotgen inspect: --symbolic needs --inertia");
}
