// The model reader's user-error sites (generator/spec/) that no other test pins exactly, one table
// row each: `rotgen emit` of the model exits 2 with one line naming the file and, where the input
// has one, the line and column, and writes no output directory.
#include "error_sites.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <tuple>

using namespace rotgen::test;
namespace fs = std::filesystem;

namespace {
const std::string parts_of = "name: top\nbody: {parts: [";
const std::string a_part = "e.g. '- box: {mass: m, size: [a, b, c], at: [x, y, z]}'";

void check_emit_refuses(const std::string& model, const std::string& line) {
    const scratch_dir out("spec_error_site_out");
    const run_result r =
        run_rotgen("emit " + model + " -o '" + out.path.string() + "'", ROTGEN_BINARY_DIR);
    check_error_line(r, line);
    CHECK(!fs::exists(out.path));
}
} // namespace

TEST_CASE("spec: each model error site gives one line with line and column, exit 2, no output",
          "[spec][errors]") {
    using row = std::tuple<std::string, std::string, std::string>;
    // the model file, "LINE:COL", the problem
    const auto [text, place, problem] = GENERATE_COPY(table<std::string, std::string, std::string>({
        row{"name: top\nparameters: [1, 2]\ninertia: [1, 1, 1]\n", "2:13",
            "'parameters' must be a mapping of name: default value"},
        row{"name: top\nparameters: {a: {value: 1}, b: {x: 2}}\ninertia: [1, 1, 1]\n", "2:33",
            "unknown field 'x' in parameter 'b'"},
        row{"name: top\nparameters: {3a: 1}\ninertia: [1, 1, 1]\n", "2:14",
            "parameter name '3a' is not an identifier"},
        row{"name: int\ninertia: [1, 1, 1]\n", "1:7",
            "the model name 'int' is reserved: it is a C++ keyword"},
        row{"name: top\ninertia: [1, 1, 1]\ngravity: 3\n", "3:10",
            "'gravity' must be {mass: M, g: g, com: [x, y, z]}"},
        row{"name: top\ninertia: [1, 1, 1]\ngravity: {mass: 1, g: 9.81, com: [0, 0]}\n", "3:34",
            "gravity 'com' must be a list of three coordinates"},
        row{"name: top\ninertia: [1, 1, 1]\npotential: [1]\n", "3:12",
            "expected a number or an expression for potential"},
        row{"name: top\nparameters: {a: 1}\ninertia: [1, 1, 1]\npotential: sqrt(-a)\n", "4:12",
            "potential is not a finite real number with the parameters' defaults (a division by "
            "zero or a logarithm of a non-positive number?)"},
        row{"name: top\ninertia: [1, 1, 1]\ntorque: [1, 2]\n", "3:9",
            "'torque' must be a list of three body-frame components"},
        row{"name: top\nbody: 3\n", "2:7",
            "'body' must be a mapping {pivot: [x, y, z], parts: [...]}"},
        row{"name: top\nbody: {pivot: [0, 0, 0]}\n", "2:7", "'body' needs 'parts'"},
        row{parts_of + "3]}\n", "2:16",
            "a part must be one of point, box, rod, cylinder, sphere with its fields, " + a_part},
        row{parts_of + "{box: {mass: 1, size: [1, 1, 1], at: [0, 0, 0]}, point: {mass: 1, at: "
                       "[0,0,0]}}]}\n",
            "2:16",
            "a part must be one of point, box, rod, cylinder, sphere with its fields, " + a_part},
        row{parts_of + "{box: {mass: 1, size: [1, 1], at: [0, 0, 0]}}]}\n", "2:38",
            "box 'size' must be its three edges [a, b, c]"},
        row{parts_of + "{sphere: {mass: 1, radius: 1, at: [0, 0, 0], hollow: 3}}]}\n", "2:69",
            "sphere 'hollow' must be true or false"},
        row{parts_of + "{point: {mass: 1, at: [0, 0]}}]}\n", "2:38",
            "point 'at' must be its centre [x, y, z] in body axes"},
        row{parts_of + "{rod: {mass: 1, length: 1, at: [0, 0, 0]}}]}\n", "2:17",
            "the rod needs 'axis'"},
        row{parts_of + "{box: {mass: 1, size: [1, 1, 1], at: [0, 0, 0], colour: red}}]}\n", "2:64",
            "unknown field 'colour' in the box"},
    }));
    INFO(text);
    const scratch_file file("spec_error_site.yaml", text);
    check_emit_refuses("spec_error_site.yaml", "spec_error_site.yaml:" + place + ": " + problem);
}

TEST_CASE("spec: a model file that cannot be read is named without a line", "[spec][errors]") {
    SECTION("a directory") {
        const scratch_dir dir("spec_error_site_dir");
        fs::create_directories(dir.path);
        check_emit_refuses(
            "spec_error_site_dir",
            "spec_error_site_dir: is a folder, not a file; give a model or scene file");
    }
    SECTION("a file over 1 MiB") {
        const scratch_file file("spec_error_site_big.yaml",
                                "name: big\ninertia: [1, 1, 1]\n" + std::string(1 << 20, '#'));
        check_emit_refuses("spec_error_site_big.yaml",
                           "spec_error_site_big.yaml: file is larger than 1 MiB");
    }
}

TEST_CASE("spec: a tensor or a potential that overflows double is refused at its key",
          "[spec][errors]") {
    using row = std::tuple<std::string, std::string, std::string>;
    // the model file, "LINE:COL", the problem
    const auto [text, place, problem] = GENERATE(table<std::string, std::string, std::string>({
        // I_yy = a^2 + b^2 - (a + b)^2/2 about the centre of mass: inf + inf - inf = NaN
        row{"name: b\nparameters: {a: 1e200, b: 2e200}\nbody:\n  parts:\n    - point: {mass: 1, "
            "at: [a, 0, 0]}\n    - point: {mass: 1, at: [b, 0, 0]}\n",
            "4:3",
            "the inertia of 'body' is not finite with the parameters' defaults (too large for "
            "double precision)"},
        // I_zz = 1e400 / 2
        row{"name: b\nbody:\n  parts:\n    - point: {mass: 1, at: [1e200, 0, 0]}\n    - point: "
            "{mass: 1, at: [0, 1e200, 0]}\n",
            "3:3",
            "the inertia of 'body' is not finite with the parameters' defaults (too large for "
            "double precision)"},
        // M g z = 1e600
        row{"name: top\ninertia: [1, 1, 1]\ngravity: {mass: 1e300, g: 1e300, com: [0, 0, 1]}\n",
            "3:10",
            "the potential with gravity is not a finite real number with the parameters' "
            "defaults"},
    }));
    INFO(text);
    const scratch_file file("spec_error_site_overflow.yaml", text);
    check_emit_refuses("spec_error_site_overflow.yaml",
                       "spec_error_site_overflow.yaml:" + place + ": " + problem);
}
