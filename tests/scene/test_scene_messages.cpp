// Messages for scene errors that point at the right place and suggest the right name.
#include "support.hpp"

#include "support/error.hpp"

#include <catch2/catch.hpp>

using namespace rotgen::test;

TEST_CASE("a missing model file is reported at the scene's model key", "[scene][errors]") {
    const scratch_file scene("no_model_scene.yaml",
                             "initial: {theta: 1}\nmodel: nosuch.yaml\ntime: {end: 1}\n");
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
