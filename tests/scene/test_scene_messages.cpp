// Messages for scene errors that point at the right place and suggest the right name.
#include "support.hpp"

#include "support/error.hpp"

#include <catch2/catch.hpp>

#include <tuple>

using namespace rotgen::test;

TEST_CASE("a missing model file is reported at the scene's model key", "[scene][errors]") {
    const scratch_file scene("no_model_scene.yaml",
                             "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, "
                             "psi_dot: 0}\nmodel: nosuch.yaml\ntime: {end: 1}\n");
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/no_model.csv";
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'");
    CHECK(r.status == 2);
    const std::string dir = std::string(ROTGEN_BINARY_DIR) + "/";
    CHECK(r.err == "rotgen: error: " + scene.path + ":2:8: cannot open the model file '" + dir +
                       "nosuch.yaml': No such file or directory\n");
    CHECK_FALSE(std::ifstream(csv).good());
}

TEST_CASE("did-you-mean counts a swapped pair of letters as one typo", "[support][errors]") {
    const std::vector<std::string> methods{"rk4", "dopri5", "dop853", "implicit_midpoint",
                                           "rosenbrock"};
    CHECK(rotgen::closest_name("dop835", methods) == "dop853"); // 1 transposition; dopri5 is 2 away
    CHECK(rotgen::closest_name("dopri", methods) == "dopri5");
    CHECK(rotgen::closest_name("rk45", methods) == "rk4");
    CHECK(rotgen::closest_name("euler", methods).empty()); // nothing close: no suggestion
}

TEST_CASE("an incomplete initial state is refused at the initial key, naming what is missing",
          "[scene][errors]") {
    const std::string model = "model: " + rotgen::test::model_path("heavy_top") + "\n";
    const std::string rates = "(phi_dot, theta_dot, psi_dot, or p_phi, p_theta, p_psi, or "
                              "omega1, omega2, omega3, or omega_x, omega_y, omega_z; nothing "
                              "defaults to 0)";
    using row = std::tuple<std::string, std::string>;
    const auto [initial, expected] = GENERATE_COPY(table<std::string, std::string>({
        row{"initial: {theta: 1}\n", "missing phi, psi and the rates " + rates},
        row{"initial: {phi: 0, theta: 1, psi: 0}\n", "missing the rates " + rates},
        row{"initial: {phi: 0, theta: 1, psi: 0, p_psi: 2}\n",
            "missing p_phi, p_theta (a state is phi, theta, psi with p_phi, p_theta, p_psi; "
            "nothing defaults to 0)"},
        row{"initial:\n  theta: 1\n  omega3: 2\n",
            "missing phi, psi, omega1, omega2 (a state is phi, theta, psi with omega1, omega2, "
            "omega3; nothing defaults to 0)"},
        row{"initial: {phi: 0, theta: 1, psi: 0, phi_dot: 0, psi_dot: 0}\n",
            "missing theta_dot (a state is phi, theta, psi with phi_dot, theta_dot, psi_dot; "
            "nothing defaults to 0)"},
    }));
    INFO(initial);
    const scratch_file scene("incomplete_scene.yaml", model + initial + "time: {end: 1}\n");
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/incomplete.csv";
    const run_result r = run_rotgen("simulate '" + scene.path + "' -o '" + csv + "'");
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: " + scene.path +
                       ":2:1: the initial state is incomplete: " + expected + "\n");
    CHECK_FALSE(std::ifstream(csv).good());
}
