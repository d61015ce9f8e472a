// Issue 14: a model whose body cannot exist is refused at the offending key, with the violated
// condition and the values: a negative mass (a part's or gravity's), a negative principal moment,
// principal moments that break the triangle inequality (I1 + I2 >= I3 and permutations), whether
// the tensor is given by `inertia:` or built from parts. The equality is the planar limit (a
// lamina, I3 = I1 + I2 by the perpendicular-axis theorem) and is accepted.
#include "error_sites.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <tuple>

using namespace rotgen::test;
namespace fs = std::filesystem;

TEST_CASE("spec: unphysical masses and moments are refused at their key", "[spec][errors]") {
    using row = std::tuple<std::string, std::string, std::string>;
    const std::string ball = "sphere: {mass: 1, radius: 1, at: [0, 0, 0]}";
    // the model after "name: top\n", "LINE:COL", the problem
    const auto [text, place, problem] = GENERATE_COPY(table<std::string, std::string, std::string>({
        row{"inertia: [-1, 2, 2]\n", "2:10",
            "inertia is not physical: a principal moment is negative (-1, 2, 2)"},
        // eigenvalues of [[1, 2], [2, 1]] are -1 and 3
        row{"inertia: [[1, 2, 0], [2, 1, 0], [0, 0, 3]]\n", "2:10",
            "inertia is not physical: a principal moment is negative (-1, 3, 3)"},
        row{"inertia: [3, 1, 1]\n", "2:10",
            "inertia is not physical: principal moments (1, 1, 3) break the triangle "
            "inequality (each at most the sum of the other two): 1 + 1 < 3"},
        row{"parameters: {a: 1, b: 5}\ninertia: [a, b, a]\n", "3:10",
            "inertia is not physical: principal moments (1, 1, 5) break the triangle "
            "inequality (each at most the sum of the other two): 1 + 1 < 5"},
        row{"inertia: [1, 1, 1]\ngravity: {mass: -1, g: 9.81, com: [0, 0, 1]}\n", "3:17",
            "gravity mass must be positive, got -1"},
        row{"parameters: {M: -2}\ninertia: [1, 1, 1]\ngravity: {mass: M, g: 9.81, com: [0, 0, "
            "1]}\n",
            "4:17", "gravity mass must be positive (with the parameters' defaults), got -2"},
        row{"body: {parts: [{" + ball + "}, {point: {mass: -1, at: [1, 0, 0]}}]}\n", "2:78",
            "point mass must be positive, got -1"},
        row{"parameters: {m: -0.5}\nbody: {parts: [{box: {mass: m, size: [1, 1, 1], at: [0, 0, "
            "0]}}]}\n",
            "3:29", "box mass must be positive (with the parameters' defaults), got -0.5"},
    }));
    INFO(text);
    const scratch_file file("spec_physical.yaml", "name: top\n" + text);
    const scratch_dir out("spec_physical_out");
    const run_result r =
        run_rotgen("emit spec_physical.yaml -o '" + out.path.string() + "'", ROTGEN_BINARY_DIR);
    check_error_line(r, "spec_physical.yaml:" + place + ": " + problem);
    CHECK(!fs::exists(out.path));
}

TEST_CASE("spec: the triangle inequality's equality (a lamina) is accepted", "[spec]") {
    // a flat box (edges 1, 2, 0): I1 = m b^2/12 = 1/3, I2 = m a^2/12 = 1/12, I3 = 5/12 = I1 + I2
    const std::string text = GENERATE(as<std::string>{}, "inertia: [1, 2, 3]\n",
                                      "body: {parts: [{box: {mass: 1, size: [1, 2, 0], at: [0, 0, "
                                      "0]}}]}\n");
    INFO(text);
    const scratch_file file("spec_lamina.yaml", "name: top\n" + text);
    const run_result r = run_rotgen("inspect spec_lamina.yaml --inertia", ROTGEN_BINARY_DIR);
    INFO(r.err);
    CHECK(r.status == 0);
    CHECK(r.err.empty());
    CHECK(r.out.find("class: asymmetric top") != std::string::npos);
}
