// Bad scene files (generator/scene/scene.cpp) that no other test reaches: exit status 2, exactly
// one line "rotgen: error: FILE:LINE:COL: problem" on stderr, and no CSV left behind. The
// messages are pinned as they are.
#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <tuple>

using namespace rotgen::test;

TEST_CASE("scene: malformed sections give one line with file, line and column", "[scene][errors]") {
    const std::string model = "model: " + model_path("heavy_top") + "\n";
    const std::string ok = "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: "
                           "0}\ntime: {end: 1}\n";
    using row = std::tuple<std::string, std::string>;
    // the scene file, the message after "rotgen: error: "
    const auto [text, line] = GENERATE_COPY(table<std::string, std::string>({
        row{model + ok + "switch_chart: maybe\n",
            "scene_errors.yaml:4:15: switch_chart must be true or false"},
        row{"model: [a]\n" + ok,
            "scene_errors.yaml:1:8: 'model' must be a file name or a model mapping"},
        row{model + "parameters: [1]\n" + ok,
            "scene_errors.yaml:2:13: 'parameters' must be a mapping of name: value"},
        row{model + "initial: [1]\ntime: {end: 1}\n",
            "scene_errors.yaml:2:10: 'initial' must be a mapping of angles and rates"},
        row{model + "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: "
                    "0}\ntime: 5\n",
            "scene_errors.yaml:3:7: 'time' must be {start, end, samples}"},
        row{model + "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: "
                    "0}\ntime: {start: 0}\n",
            "scene_errors.yaml:3:7: time needs 'end'"},
        row{model + "initial: {theta: 1, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: "
                    "0}\ntime: {end: 1, samples: 1.5}\n",
            "scene_errors.yaml:3:25: time samples must be a whole number from 2 to 1e8"},
        row{model + ok + "integrator: dop853\n", "scene_errors.yaml:4:13: 'integrator' must be "
                                                 "{method, rtol, atol} or {method, step} (a "
                                                 "step: fixed steps, no error control)"},
        row{model + ok + "integrator: {method: dop853, rtol: 1e-16}\n",
            "scene_errors.yaml:4:36: integrator rtol below 1e-15 cannot be met in double "
            "precision"},
        row{model + ok + "integrator: {method: rk4, step: 2}\n",
            "scene_errors.yaml:4:33: integrator step is longer than the time span"},
        row{model + ok + "record: theta\n",
            "scene_errors.yaml:4:9: 'record' must be a list of quantities"},
        row{model + ok + "record: [theta, theta]\n",
            "scene_errors.yaml:4:17: 'theta' is recorded twice"},
    }));
    INFO(text);
    const scratch_file scene("scene_errors.yaml", text);
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/scene_errors.csv";
    std::remove(csv.c_str());
    const run_result r =
        run_rotgen("simulate scene_errors.yaml -o '" + csv + "'", ROTGEN_BINARY_DIR);
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err == "rotgen: error: " + line + "\n");
    CHECK(read_file(csv).empty()); // no output file
}
