// Scene values written as expressions of the model language (generator/scene/values.cpp): exact
// where possible, located errors where not, and a plain number read exactly as before.
#include "support.hpp"

#include "run/kinematics.hpp"
#include "scene/scene.hpp"
#include "support/error.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace rotgen;
using namespace rotgen::test;

namespace {

const long double pi_ld = 3.141592653589793238462643383279502884L;

std::string heavy_top_scene(const std::string& parameters, const std::string& initial) {
    return "model: " + model_path("heavy_top") + "\n" + parameters + "initial: {" + initial +
           "}\ntime: {end: 0.5, samples: 6}\nrecord: [theta, psi_dot, p_psi]\n";
}

} // namespace

TEST_CASE("initial values are expressions in pi and the model's parameters, evaluated exactly",
          "[scene][values]") {
    const scratch_file file("values_exact.yaml",
                            heavy_top_scene("parameters: {I1: 2, I3: I1/4}\n",
                                            "phi: 0, theta: pi/3, psi: -pi/4, phi_dot: 0, "
                                            "theta_dot: 0, psi_dot: 2*pi*50*I3"));
    const scene_spec scene = load_scene(file.path);
    CHECK(scene.parameters[1] == 0.5); // I3 = I1/4 with the override I1 = 2
    CHECK(scene.angles[1] == static_cast<double>(pi_ld / 3));
    const derivation d = derive(scene.model);
    const initial_kinematics k = initial_kinematics_of(scene, d);
    // Held in long double from a 30-digit evaluation: within one long-double ulp of the truth.
    // Through a double the error would be ~1e-17 (pi/3 rounded), far above these bounds.
    CHECK(std::abs(k.q[1] - pi_ld / 3) <= 2e-19L);
    CHECK(std::abs(k.q[2] + pi_ld / 4) <= 2e-19L);
    CHECK(std::abs(k.qd[2] - 50 * pi_ld) <= 2e-17L); // 2 pi 50 I3 = 50 pi (ulp 1.4e-17)
    // p_psi = I3 (phi_dot cos theta + psi_dot) (5.76) = 25 pi
    CHECK(std::abs(k.p[2] - 25 * pi_ld) <= 1e-17L);
}

TEST_CASE("a number and the expression of the same value give identical runs", "[scene][values]") {
    const scratch_file a("values_number.yaml",
                         heavy_top_scene("", "phi: 0, theta: 0.5, psi: 0, phi_dot: 0, "
                                             "theta_dot: 0, psi_dot: 30"));
    const scratch_file b("values_expression.yaml",
                         heavy_top_scene("", "phi: 0, theta: 1/2, psi: 0*pi, phi_dot: 0, "
                                             "theta_dot: 0, psi_dot: 60*I3"));
    const std::string dir = std::string(ROTGEN_BINARY_DIR) + "/";
    REQUIRE(run_rotgen("simulate '" + a.path + "' -o '" + dir + "values_a.csv'").status == 0);
    REQUIRE(run_rotgen("simulate '" + b.path + "' -o '" + dir + "values_b.csv'").status == 0);
    const std::string csv_a = read_file(dir + "values_a.csv");
    CHECK(csv_a.size() > 100);
    CHECK(csv_a == read_file(dir + "values_b.csv"));
    std::remove((dir + "values_a.csv").c_str());
    std::remove((dir + "values_b.csv").c_str());
}

TEST_CASE("a bad expression in a scene is reported at its place in the scene file",
          "[scene][values][errors]") {
    const std::string rest = "phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 1";
    using row = std::tuple<std::string, std::string, std::string>;
    const auto [parameters, initial,
                expected] = GENERATE_COPY(table<std::string, std::string, std::string>({
        row{"", "theta: thta, " + rest, ":2:18: unknown symbol 'thta' in initial theta"},
        row{"", "theta: pi/2 +, " + rest, ":2:24: unexpected end of expression in initial theta"},
        row{"", "theta: sqrt(-1), " + rest, ":2:18: initial theta = sqrt(-1) is not a real number"},
        row{"", "theta: exp(1000), " + rest,
            ":2:18: initial theta = exp(1000) is not a finite double"},
        row{"", "theta: 1, psi_dot: 1e-200^2, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0",
            ":2:30: initial psi_dot = 1e-200^2 must be 0 or at least 2.2e-308 in magnitude"},
        row{"parameters: {I1: I3, I3: 2*I1}\n", "theta: 1, " + rest,
            ":2:18: parameter 'I1' is defined in terms of itself"},
        row{"parameters: {h: length}\n", "theta: 1, " + rest,
            ":2:17: unknown symbol 'length' in parameter 'h'"},
    }));
    INFO(initial);
    const scratch_file file("values_errors.yaml", heavy_top_scene(parameters, initial));
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/values_errors.csv";
    const run_result r = run_rotgen("simulate '" + file.path + "' -o '" + csv + "'");
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: " + file.path + expected + "\n");
    CHECK_FALSE(std::ifstream(csv).good());
}
