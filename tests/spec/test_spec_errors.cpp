// Bad model files: each gives exit status 2 and one line "rotgen: error: FILE:LINE:COL: problem",
// with nothing on stdout (DESIGN.md "Bad input").
#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <tuple>

using namespace rotgen::test;

namespace {
const std::string top = "name: top\nparameters: {I1: 1.0, I3: 0.5}\ninertia: [I1, I1, I3]\n";
}

TEST_CASE("bad model files give one clear line and exit 2", "[spec][errors]") {
    using row = std::tuple<std::string, std::string, std::string, std::string>;
    // name, file contents, expected "LINE:COL", expected text in the message
    const auto [name, text, place,
                problem] = GENERATE(table<std::string, std::string, std::string, std::string>({
        row{"malformed YAML", "name: top\ninertia: [1, 1, 1\n", "3:1", "malformed YAML"},
        row{"tab-broken YAML", "name: top\n  inertia: [1, 1, 1]\n", "2:10", "malformed YAML"},
        row{"empty file", "", "1:1", "expected a YAML mapping"},
        row{"a list, not a mapping", "- 1\n- 2\n", "1:1", "expected a YAML mapping"},
        row{"missing name", "inertia: [1, 1, 1]\n", "1:1", "missing field 'name'"},
        row{"missing inertia", "name: top\n", "1:1", "missing field 'inertia'"},
        row{"duplicate field", "name: top\nname: other\ninertia: [1, 1, 1]\n", "2:1",
            "duplicate field 'name'"},
        row{"duplicate parameter", "name: top\nparameters: {a: 1, a: 2}\ninertia: [1, 1, 1]\n",
            "2:20", "duplicate field 'a' in parameters"},
        row{"unknown field", "name: top\ninertia: [1, 1, 1]\npotentail: 0\n", "3:1",
            "unknown field 'potentail' in the model; did you mean 'potential'?"},
        row{"unknown symbol", top + "potential: 2*cos(thta)\n", "4:18",
            "unknown symbol 'thta' in potential; did you mean 'theta'?"},
        row{"unknown function", top + "potential: coss(theta)\n", "4:12",
            "unknown function 'coss' in potential; did you mean 'cos'?"},
        row{"syntax error", top + "potential: 2*cos(theta) +\n", "4:26",
            "unexpected end of expression in potential"},
        row{"unbalanced parenthesis", top + "potential: \"(1 + cos(theta)\"\n", "4:28",
            "expected ')'"},
        row{"bad character", top + "potential: 2 $ theta\n", "4:14", "unexpected character '$'"},
        row{"wrong argument count", top + "potential: atan2(theta)\n", "4:12",
            "function 'atan2' takes 2 arguments, got 1"},
        row{"division by zero", top + "potential: 1/(theta - theta)\n", "4:13", "division by zero"},
        row{"a sum to a huge power (fuzzing: derivation blow-up)",
            top + "potential: (cos(theta)/2 + sin(psi)/2)^1000\n", "4:39",
            "a sum raised to a power above 32 is not supported"},
        row{"division by a zero parameter",
            "name: top\nparameters: {a: 0}\ninertia: [1, 1, 1]\npotential: 1/a\n", "4:12",
            "not a finite real number with the parameters' defaults"},
        row{"reserved name: coordinate", "name: top\nparameters: {psi: 1}\ninertia: [1, 1, 1]\n",
            "2:14", "'psi' cannot be a parameter name"},
        row{"reserved name: GiNaC constant", "name: top\nparameters: {I: 1}\ninertia: [I, I, I]\n",
            "2:14", "'I' cannot be a parameter name: it is a built-in constant"},
        row{"reserved name: special function",
            "name: top\nparameters: {beta: 1}\ninertia: [1, 1, 1]\n", "2:14",
            "'beta' cannot be a parameter name"},
        row{"reserved name: generated code", "name: top\nparameters: {T: 1}\ninertia: [1, 1, 1]\n",
            "2:14", "'T' cannot be a parameter name: it is used by the generated code"},
        row{"model name not an identifier", "name: 3top\ninertia: [1, 1, 1]\n", "1:7",
            "must be a C++ identifier"},
        row{"non-numeric default", "name: top\nparameters: {a: fast}\ninertia: [1, 1, 1]\n", "2:17",
            "must be a finite number"},
        row{"NaN default", "name: top\nparameters: {a: .nan}\ninertia: [1, 1, 1]\n", "2:17",
            "must be a finite number"},
        row{"inertia of the wrong shape", "name: top\ninertia: [1, 1]\n", "2:10",
            "'inertia' must be three principal moments"},
        row{"inertia not symmetric", "name: top\ninertia: [[2, 0.1, 0], [0.2, 2, 0], [0, 0, 2]]\n",
            "2:25", "inertia is not symmetric"},
        row{"negative moment", "name: top\ninertia: [-1, 2, 2]\n", "2:10",
            "a principal moment is negative"},
        row{"triangle inequality", "name: top\ninertia: [1, 1, 3]\n", "2:10",
            "break the triangle inequality (each at most the sum of the other two): 1 + 1 < 3"},
        row{"symbolic inertia, unphysical defaults",
            "name: top\nparameters: {a: 1, b: 5}\ninertia: [a, a, b]\n", "3:10",
            "triangle inequality"},
        row{"unknown field after a valid model", top + "potential: 0\nfoo: 1\n", "5:1",
            "unknown field 'foo'"},
        row{"angle in inertia", "name: top\ninertia: [1, 1, theta]\n", "2:17",
            "unknown symbol 'theta' in inertia"},
        row{"time in potential", top + "potential: cos(t)\n", "4:16",
            "unknown symbol 't' in potential"},
        row{"gravity without com", top + "gravity: {mass: 1, g: 9.81}\n", "4:10",
            "gravity needs 'com'"},
        // today's V would be the sum: the gravity potential counted again inside `potential`
        row{"gravity then potential",
            top + "gravity: {mass: 1, g: 9.81, com: [0, 0, 1]}\npotential: 9.81*cos(theta)\n",
            "5:1", "give 'gravity' or 'potential', not both"},
        row{"potential then gravity",
            top + "potential: 9.81*cos(theta)\ngravity: {mass: 1, g: 9.81, com: [0, 0, 1]}\n",
            "5:1", "give 'gravity' or 'potential', not both"},
        row{"damping of the wrong length", top + "damping: [1, 2]\n", "4:10",
            "'damping' must be one coefficient, a list of three, or {body: [c1, c2, c3]}"},
        row{"torque not a list", top + "torque: 1\n", "4:9", "'torque' must be a list of three"},
        row{"inertia and body together",
            "name: top\ninertia: [1, 1, 1]\nbody: {parts: [{point: {mass: 1, at: [1, 0, 0]}}]}\n",
            "3:7", "give either 'inertia' or 'body'"},
        row{"body without parts", "name: top\nbody: {parts: []}\n", "2:15",
            "body 'parts' must be a non-empty list"},
        row{"unknown part",
            "name: top\nbody: {parts: [{cylindre: {mass: 1, radius: 1, length: 1, at: [0, 0, 0], "
            "axis: [0, 0, 1]}}]}\n",
            "2:17", "unknown part 'cylindre'"},
        row{"part without mass",
            "name: top\nbody: {parts: [{box: {size: [1, 1, 1], at: [0, 0, 0]}}]}\n", "2:17",
            "the box needs 'mass'"},
        row{"part of negative size",
            "name: top\nbody: {parts: [{box: {mass: 1, size: [1, -1, 1], at: [0, 0, 0]}}]}\n",
            "2:42", "box size must be non-negative, got -1"},
        row{"part axis of zero length",
            "name: top\nbody: {parts: [{rod: {mass: 1, length: 1, at: [0, 0, 0], axis: [0, 0, "
            "0]}}]}\n",
            "2:64", "the rod axis has zero length"},
    }));
    INFO(name);
    const scratch_file file("bad_model.yaml", text);
    const run_result r = run_rotgen("inspect bad_model.yaml", ROTGEN_BINARY_DIR);
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    // exactly one line
    REQUIRE(!r.err.empty());
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    const std::string prefix = "rotgen: error: bad_model.yaml:" + place + ": ";
    CHECK(r.err.rfind(prefix, 0) == 0);
    CHECK(r.err.find(problem) != std::string::npos);
}

TEST_CASE("a missing model file is a user error", "[spec][errors]") {
    const run_result r = run_rotgen("inspect no_such_model.yaml", ROTGEN_BINARY_DIR);
    CHECK(r.status == 2);
    CHECK(r.err ==
          "rotgen: error: no_such_model.yaml: cannot open file: No such file or directory\n");
}

TEST_CASE("bad command lines are user errors", "[cli][errors]") {
    CHECK(run_rotgen("frobnicate").status == 2);
    CHECK(run_rotgen("inspect").status == 2);
    const run_result r = run_rotgen("inspect '" + model_path("heavy_top") + "' --format yaml");
    CHECK(r.status == 2);
    CHECK(r.err.find("unknown format 'yaml'") != std::string::npos);
    CHECK(run_rotgen("inspect '" + model_path("heavy_top") + "' --frobnicate").status == 2);
}

TEST_CASE("expressions: decimals are exact, ** and ^ are powers", "[spec]") {
    const scratch_file file("exact_model.yaml",
                            "name: exact\nparameters: {a: 0.1}\ninertia: [1, 1, 1]\n"
                            "potential: 0.1*a**2 + 0.2*a^2 + 1e-1*cos(theta)\n");
    const rotgen::model_spec spec =
        rotgen::load_model(std::string(ROTGEN_BINARY_DIR) + "/exact_model.yaml");
    const GiNaC::ex a = spec.parameter_names().at("a");
    const GiNaC::ex expected = GiNaC::numeric(3, 10) * GiNaC::pow(a, 2) +
                               GiNaC::numeric(1, 10) * GiNaC::cos(rotgen::symbols().q[1]);
    CHECK((spec.potential - expected).expand().is_zero());
}
