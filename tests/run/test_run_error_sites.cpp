// The run engine's user-error sites (generator/run/engine.cpp, generator/run/kernels.cpp) that no
// other test pins, one table row each: `rotgen simulate` of the scene exits 2 with one line naming
// the scene file, line and column, prints nothing on stdout and writes no CSV.
#include "error_sites.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <tuple>

using namespace rotgen::test;

TEST_CASE("run: each engine error site gives one line with line and column, exit 2, no output",
          "[run][errors]") {
    using row = std::tuple<std::string, std::string>;
    // the scene after its "model:" line, the whole message after "rotgen: error: "
    const auto [rest, line] = GENERATE(table<std::string, std::string>({
        // engine.cpp: momenta at theta = 0, in an Euler-angle form and in the body form
        row{"initial: {theta: 0, p_phi: 1, p_theta: 0, p_psi: 1, phi: 0, psi: 0}\n",
            "run_error_site.yaml:2:10: momenta cannot give the rates at theta = 0 or pi (the mass "
            "matrix is singular there); give body omega1..3 instead"},
        row{"form: body\ninitial: {theta: 0, p_phi: 1, p_theta: 0, p_psi: 1, phi: 0, psi: 0}\n",
            "run_error_site.yaml:3:10: momenta cannot give the rates at theta = 0 or pi (the mass "
            "matrix is singular there); give body omega1..3 instead"},
        // engine.cpp: a finite initial rate whose body omega overflows double
        row{"initial: {theta: 0.1, phi_dot: 1.5e308, theta_dot: 0, psi_dot: 1.5e308, phi: 0, psi: "
            "0}\n",
            "run_error_site.yaml:2:10: initial values too large for double precision: omega3 = "
            "inf at t = 0.0; give smaller initial rates or momenta, or rescale the model's units"},
        row{"initial: {theta: 0.1, p_phi: 1.5e308, p_theta: 0, p_psi: 1.5e308, phi: 0, psi: 0}\n",
            "run_error_site.yaml:2:10: initial values too large for double precision: psi_dot = "
            "inf at t = 0.0; give smaller initial rates or momenta, or rescale the model's units"},
        // kernels.cpp: a body axis the form does not give
        row{"form: reduced\ninitial: {theta: 1, omega1: 0.1, omega2: 0, omega3: 1, phi: 0, psi: "
            "0}\n"
            "record: [body_x]\n",
            "run_error_site.yaml:4:10: the reduced form does not give 'body_x'"},
    }));
    INFO(rest);
    const scratch_file file("run_error_site.yaml", "model: " + model_path("heavy_top") + "\n" +
                                                       rest + "time: {end: 1, samples: 3}\n");
    const scratch_dir csv("run_error_site.csv"); // removed before and after
    const run_result r =
        run_rotgen("simulate run_error_site.yaml -o run_error_site.csv", ROTGEN_BINARY_DIR);
    check_error_line(r, line);
    CHECK(!std::filesystem::exists(csv.path));
}
