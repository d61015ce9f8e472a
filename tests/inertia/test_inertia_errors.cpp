// Bad `body:` sections (inertia from parts): each gives exit status 2 and one line
// "rotgen: error: FILE:LINE:COL: problem" pointing at the offending node, nothing on stdout.
#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <tuple>

using namespace rotgen::test;

namespace {
// Line 5 holds the part under test, from column 7 on.
const std::string head = "name: b\nparameters: {m: 1.5, l: 0.4, k: 0}\nbody:\n  parts:\n    - ";
} // namespace

TEST_CASE("inertia: bad parts give one clear line with their place and exit 2",
          "[inertia][spec][errors]") {
    using row = std::tuple<std::string, std::string, std::string, std::string>;
    // name, file contents, expected "LINE:COL", expected text in the message
    const auto [name, text, place,
                problem] = GENERATE(table<std::string, std::string, std::string, std::string>({
        row{"inertia and body together",
            "name: b\ninertia: [1, 1, 1]\nbody: {parts: [{point: {mass: 1, at: [1, 0, 0]}}]}\n",
            "3:7", "give either 'inertia' or 'body' (the inertia from parts), not both"},
        row{"neither inertia nor body", "name: b\n", "1:1",
            "missing field 'inertia' (or 'body', the inertia from parts)"},
        row{"body not a mapping", "name: b\nbody: [1]\n", "2:7",
            "'body' must be a mapping {pivot: [x, y, z], parts: [...]}"},
        row{"body without parts", "name: b\nbody: {pivot: [0, 0, 0]}\n", "2:7",
            "'body' needs 'parts'"},
        row{"unknown field in body", "name: b\nbody: {prts: []}\n", "2:8",
            "unknown field 'prts' in body; did you mean 'parts'?"},
        row{"empty list of parts", "name: b\nbody: {parts: []}\n", "2:15",
            "body 'parts' must be a non-empty list of parts"},
        row{"parts not a list", "name: b\nbody:\n  parts: {box: 1}\n", "3:10",
            "body 'parts' must be a non-empty list"},
        row{"pivot of the wrong shape",
            "name: b\nbody: {pivot: [0, 0], parts: [{sphere: {mass: 1, radius: 1, at: [0, 0, "
            "0]}}]}\n",
            "2:15", "body pivot must be a list of three coordinates"},
        row{"unknown kind of part",
            head + "cylindre: {mass: m, radius: l, length: l, at: [0, 0, 0], axis: [0, 0, 1]}\n",
            "5:7",
            "unknown part 'cylindre' (expected point, box, rod, cylinder, sphere); did you mean "
            "'cylinder'?"},
        row{"a part that is a bare word", head + "sphere\n", "5:7",
            "a part must be one of point, box, rod, cylinder, sphere"},
        row{"two kinds in one part",
            head +
                "{point: {mass: m, at: [0, 0, 0]}, sphere: {mass: m, radius: l, at: [0, 0, 0]}}\n",
            "5:7", "a part must be one of"},
        row{"fields not a mapping", head + "box: [1, 2]\n", "5:12",
            "a box needs a mapping of its fields {mass: ..., size: ..., at: ..., rotation: ...}"},
        row{"no fields at all", head + "sphere:\n", "5:7",
            "a sphere needs a mapping of its fields"},
        row{"missing mass", head + "box: {size: [l, l, l], at: [0, 0, 0]}\n", "5:7",
            "the box needs 'mass'"},
        row{"missing position", head + "sphere: {mass: m, radius: l}\n", "5:7",
            "the sphere needs 'at' (its centre in body axes)"},
        row{"missing size", head + "box: {mass: m, at: [0, 0, 0]}\n", "5:7",
            "the box needs 'size'"},
        row{"missing axis", head + "rod: {mass: m, length: l, at: [0, 0, 0]}\n", "5:7",
            "the rod needs 'axis'"},
        row{"missing radius",
            head + "cylinder: {mass: m, length: l, at: [0, 0, 0], axis: [0, 0, 1]}\n", "5:7",
            "the cylinder needs 'radius'"},
        row{"unknown field in a part", head + "box: {mass: m, sise: [l, l, l], at: [0, 0, 0]}\n",
            "5:22", "unknown field 'sise' in the box; did you mean 'size'?"},
        row{"a field of another kind", head + "point: {mass: m, at: [0, 0, 0], radius: l}\n",
            "5:39", "unknown field 'radius' in the point"},
        row{"negative mass", head + "point: {mass: -2, at: [1, 0, 0]}\n", "5:21",
            "point mass must be positive, got -2"},
        row{"zero mass", head + "point: {mass: 0, at: [1, 0, 0]}\n", "5:21",
            "point mass must be positive, got 0"},
        row{"negative mass through a parameter's default",
            "name: b\nparameters: {m: -1.5}\nbody:\n  parts:\n    - point: {mass: m, at: [1, 0, "
            "0]}\n",
            "5:21", "point mass must be positive (with the parameters' defaults), got -1.5"},
        row{"negative edge", head + "box: {mass: m, size: [l, -l, l], at: [0, 0, 0]}\n", "5:32",
            "box size must be non-negative (with the parameters' defaults), got -0.4"},
        row{"negative radius", head + "sphere: {mass: m, radius: -0.1, at: [0, 0, 0]}\n", "5:33",
            "sphere radius must be non-negative, got -0.1"},
        row{"negative length",
            head + "cylinder: {mass: m, radius: l, length: -l, at: [0, 0, 0], axis: [0, 0, 1]}\n",
            "5:46", "cylinder length must be non-negative"},
        row{"axis of zero length",
            head + "rod: {mass: m, length: l, at: [0, 0, 0], axis: [0, 0, 0]}\n", "5:54",
            "the rod axis has zero length"},
        row{"axis of zero length through a parameter's default",
            head + "rod: {mass: m, length: l, at: [0, 0, 0], axis: [k, 0, 0]}\n", "5:54",
            "the rod axis has zero length with the parameters' defaults"},
        row{"size of the wrong shape", head + "box: {mass: m, size: [l, l], at: [0, 0, 0]}\n",
            "5:28", "box 'size' must be its three edges [a, b, c]"},
        row{"position of the wrong shape", head + "point: {mass: m, at: 1}\n", "5:28",
            "point 'at' must be its centre [x, y, z] in body axes"},
        row{"rotation of the wrong shape",
            head + "box: {mass: m, size: [l, l, l], at: [0, 0, 0], rotation: [1, 2]}\n", "5:64",
            "box rotation must be z-x-z Euler angles [phi, theta, psi]"},
        row{"hollow neither true nor false",
            head + "sphere: {mass: m, radius: l, at: [0, 0, 0], hollow: maybe}\n", "5:59",
            "sphere 'hollow' must be true or false"},
        row{"unknown symbol in a part", head + "point: {mass: m, at: [l, 0, thta]}\n", "5:35",
            "unknown symbol 'thta' in point 'at'"},
        row{"a part cannot depend on the angles", head + "point: {mass: m, at: [l, 0, theta]}\n",
            "5:35", "unknown symbol 'theta' in point 'at'"},
        // a body on a line is a linear rotor, reported by inspect --inertia (test_rotor.cpp)
        row{"a single point mass at the pivot",
            "name: b\nbody:\n  parts:\n    - point: {mass: 1, at: [0, 0, 0]}\n", "3:3",
            "the inertia of 'body' has every principal moment zero"},
        row{"gravity without g",
            head + "sphere: {mass: m, radius: l, at: [0, 0, 0]}\ngravity: {mass: 1}\n", "6:10",
            "gravity needs 'g'"},
    }));
    INFO(name);
    const scratch_file file("bad_parts.yaml", text);
    const run_result r = run_rotgen("inspect bad_parts.yaml --inertia", ROTGEN_BINARY_DIR);
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    REQUIRE(!r.err.empty());
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    const std::string prefix = "rotgen: error: bad_parts.yaml:" + place + ": ";
    CHECK(r.err.rfind(prefix, 0) == 0);
    CHECK(r.err.find(problem) != std::string::npos);
}
