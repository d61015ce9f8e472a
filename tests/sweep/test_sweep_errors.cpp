// rotgen sweep: bad sweep input is refused with one located line, exit 2, and nothing written.
#include "support.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <tuple>

using namespace rotgen::test;

namespace {

bool exists(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0;
}

} // namespace

TEST_CASE("sweep: bad sweep input gives one located line, exit 2, and no output",
          "[sweep][errors]") {
    using row = std::tuple<std::string, std::string, std::string>; // sweep block, --vary, message
    const auto [block, vary, message] = GENERATE(table<std::string, std::string, std::string>({
        row{"sweep:\n  vary:\n    initial.thta: {values: [1]}\n", "",
            "sweep_bad.yaml:7:5: unknown sweep key 'initial.thta' for this scene; did you mean "
            "'initial.theta'?"},
        row{"sweep:\n  vary:\n    parameters.h: {from: 1, to: 1, count: 4}\n", "",
            "sweep_bad.yaml:7:43: empty range: from = to = 1.0 with count 4.0 (give {values: "
            "[...]} for repeated values)"},
        row{"sweep:\n  vary:\n    parameters.h: {values: []}\n", "",
            "sweep_bad.yaml:7:28: empty range: values must be a non-empty list of numbers"},
        row{"sweep:\n  vary:\n    initial.theta: {from: 0.1, to: 1, count: 0}\n", "",
            "sweep_bad.yaml:7:46: count must be a whole number from 1 to 1e8"},
        row{"sweep:\n  mode: zip\n  vary:\n    initial.theta: {values: [0.1, 0.2]}\n"
            "    parameters.h: {values: [1, 2, 3]}\n",
            "",
            "sweep_bad.yaml:9:5: zip lengths differ: 'parameters.h' has 3 values, "
            "'initial.theta' has 2"},
        row{"sweep:\n  vary:\n    initial.theta: {values: [0.1, 4]}\n", "",
            "sweep_bad.yaml:7:5: initial theta = 4.0 is outside [0, pi] (z-x-z Euler angles)"},
        row{"sweep:\n  mode: sideways\n", "",
            "sweep_bad.yaml:6:9: unknown sweep mode 'sideways' (expected grid, zip or random)"},
        row{"", "--vary initial.omega1=0:1:3",
            "rotgen sweep --vary initial.omega1=0:1:3: unknown sweep key 'initial.omega1' for "
            "this scene; did you mean 'initial.theta'?"},
        row{"", "--vary parameters.h=0.1:0.2:0",
            "rotgen sweep --vary parameters.h=0.1:0.2:0: count must be a whole number from 1 to "
            "1e8"},
        row{"", "--vary parameters.h=0.1:0.2",
            "rotgen sweep --vary parameters.h=0.1:0.2: expected KEY=FROM:TO:COUNT"},
        row{"", "",
            "sweep_bad.yaml:1:1: nothing to vary: give a sweep: block with vary: or --vary "
            "KEY=FROM:TO:COUNT"},
    }));
    const scratch_file scene(
        "sweep_bad.yaml",
        "model: " + model_path("heavy_top") +
            "\ninitial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}\n"
            "time: {end: 1, samples: 11}\nrecord: [theta]\n" +
            block);
    const std::string dir = std::string(ROTGEN_BINARY_DIR) + "/sweep_bad_out";
    const run_result r = run_rotgen("sweep '" + scene.path + "' -o '" + dir + "' " + vary);
    INFO(r.err);
    CHECK(r.status == 2);
    const std::string expected = "rotgen: error: " + std::string(ROTGEN_BINARY_DIR) + "/" + message;
    const std::string cli = "rotgen: error: " + message;
    CHECK((r.err == expected + "\n" || r.err == cli + "\n"));
    CHECK(!exists(dir));
}
