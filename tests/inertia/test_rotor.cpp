// Linear rotors (issue 14; the chapter's Example 5.4 and section 5.5): the zero principal moment
// of a body on a line is found exactly (the eigensolver gives 1e-17), the body is classified as a
// rotor and `inspect --inertia` reports it; the three-angle commands refuse it at its key, and
// emit writes its rotor form (derive/rotor.hpp).
#include "error_sites.hpp"
#include "inertia/inertia.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <tuple>

using namespace rotgen;
using namespace rotgen::test;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}

GiNaC::ex parameter_symbol(const model_spec& spec, const std::string& name) {
    for (const auto& p : spec.parameters)
        if (p.name == name) return p.symbol;
    FAIL("no parameter " << name);
    return 0;
}

// sin² → 1 − cos², expanded: identically zero expressions become 0.
bool identically_zero(const GiNaC::ex& e) {
    const GiNaC::ex x = GiNaC::wild(0);
    return GiNaC::normal(e.expand()
                             .subs(GiNaC::pow(GiNaC::sin(x), 2) == 1 - GiNaC::pow(GiNaC::cos(x), 2),
                                   GiNaC::subs_options::algebraic)
                             .expand())
        .is_zero();
}

} // namespace

TEST_CASE("rotor: the dumbbell's tensor is the chapter's and its moments are exact",
          "[inertia][rotor]") {
    const model_spec spec = load_model(model_path("dumbbell"));
    REQUIRE(spec.rotor);
    const GiNaC::ex m1 = parameter_symbol(spec, "m1"), m2 = parameter_symbol(spec, "m2");
    const GiNaC::ex r1 = parameter_symbol(spec, "r1"), r2 = parameter_symbol(spec, "r2");
    const GiNaC::ex a = parameter_symbol(spec, "alpha");
    // Example 5.4: I = (m1 r1² + m2 r2²) [[cos², −sin cos, 0], [−sin cos, sin², 0], [0, 0, 1]]
    const GiNaC::ex k = m1 * r1 * r1 + m2 * r2 * r2;
    const GiNaC::ex s = GiNaC::sin(a), c = GiNaC::cos(a);
    const matrix3 chapter = {{{k * c * c, -k * s * c, 0}, {-k * s * c, k * s * s, 0}, {0, 0, k}}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            INFO(i << j << " " << spec.inertia[i][j]);
            CHECK(identically_zero(spec.inertia[i][j] - chapter[i][j]));
        }
    CHECK(exact_zero_moments(spec.inertia) == 1);
    const inertia_report r = analyse_inertia(spec.inertia, spec.parameter_defaults());
    CHECK(r.kind == top_class::rotor);
    REQUIRE(r.principal.exact_moments);
    CHECK(r.principal.moments[0].is_zero());
    CHECK(identically_zero(r.principal.moments[1] - k));
    CHECK(identically_zero(r.principal.moments[2] - k));
    // the line along r1 = (sin alpha, cos alpha, 0) at alpha = 0.5
    CHECK(r.principal.axis_values[0][0] == Approx(std::sin(0.5)).margin(1e-15));
    CHECK(r.principal.axis_values[0][1] == Approx(std::cos(0.5)).margin(1e-15));
}

TEST_CASE("rotor: exact zero moments, counted", "[inertia][rotor]") {
    using row = std::tuple<matrix3, int>;
    const matrix3 zero = {{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
    auto [tensor, zeros] = GENERATE_COPY(table<matrix3, int>({
        row{{{{1, 0, 0}, {0, 2, 0}, {0, 0, 3}}}, 0},
        row{{{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, 1},
        // two points at ±(1, 1, 1): 2 (3·1 − d dᵀ), rank 2
        row{{{{4, -2, -2}, {-2, 4, -2}, {-2, -2, 4}}}, 1},
        row{{{{1, 1, 0}, {1, 1, 0}, {0, 0, 0}}}, 2},
        row{zero, 3},
    }));
    CHECK(exact_zero_moments(tensor) == zeros);
}

TEST_CASE("rotor: inspect --inertia reports the dumbbell", "[inertia][rotor][inspect]") {
    const run_result r = run_rotgen("inspect '" + model_path("dumbbell") + "' --inertia");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.err.empty());
    CHECK(contains(r.out, "principal moments and axes (moments exact, axes numeric"));
    CHECK(contains(r.out, "  I1 = 0  along (0.4794255386042031, 0.8775825618903728, 0)\n"));
    CHECK(contains(r.out, "  I2 = m1*r1**2 + m2*r2**2 = 0.06  along "));
    CHECK(contains(r.out, "  I3 = m1*r1**2 + m2*r2**2 = 0.06  along "));
    CHECK(contains(r.out, "class: rotor (one principal moment zero, the other two equal)\n"));
    CHECK(contains(r.out, "a linear rotor (Example 5.4)"));
    CHECK(contains(r.out, "axis 1: none: the line of a rotor"));
}

TEST_CASE("rotor: inspect prints a rotor's equations, bench refuses it, emit writes its form",
          "[inertia][rotor][errors]") {
    const std::string body = "name: rod\nbody:\n  parts:\n    - point: {mass: 1, at: [1, 1, 1]}\n"
                             "    - point: {mass: 1, at: [-1, -1, -1]}\n";
    const scratch_file file("rotor_site.yaml", body);
    // inspect: text, LaTeX and JSON, with and without --inertia (the equations themselves are
    // checked against SymPy by tests/python/rotor_sympy.py --inspect)
    for (const std::string options :
         {"", " --format latex", " --format json", " --inertia --format json"}) {
        INFO(options);
        const run_result r = run_rotgen("inspect rotor_site.yaml" + options, ROTGEN_BINARY_DIR);
        INFO(r.err);
        CHECK(r.status == 0);
        CHECK(r.err.empty());
        const bool json = options.find("json") != std::string::npos;
        const bool latex = options.find("latex") != std::string::npos;
        CHECK(contains(r.out,
                       json    ? "\"coordinates\": [\"phi\", \"theta\"]"
                       : latex ? "p_{\\varphi} &= 6 \\dot{\\varphi} \\sin^{2}\\left(\\theta\\right)"
                               : "  p_phi = 6*phi_dot*sin(theta)**2\n"));
        if (json) CHECK(contains(r.out, "\"inertia\": {") == contains(options, "--inertia"));
    }
    const scratch_file scene("rotor_site_scene.yaml",
                             "model: rotor_site.yaml\ninitial: {phi: 0, theta: 1, phi_dot: 1, "
                             "theta_dot: 0}\ntime: {end: 1}\n");
    const scratch_dir bench_out("rotor_site_bench");
    check_error_line(
        run_rotgen("bench rotor_site_scene.yaml --quick -o '" + bench_out.path.string() + "'",
                   ROTGEN_BINARY_DIR),
        "rotor_site.yaml:3:3: model 'rod' is a linear rotor (a body on a line, "
        "Example 5.4): bench compares the three-angle forms and their peers "
        "(Boost.Odeint, CVODE) on them, and a rotor has one form of two angles, "
        "rotor; run it with 'rotgen simulate' or 'rotgen sweep'");
    CHECK(!fs::exists(bench_out.path));
    // emit writes the rotor form (tests/run/test_rotor_run.cpp checks its equations); another
    // form is refused at the rotor's key
    const scratch_dir out("rotor_site_out");
    const run_result e =
        run_rotgen("emit rotor_site.yaml -o '" + out.path.string() + "'", ROTGEN_BINARY_DIR);
    CHECK(e.status == 0);
    CHECK(fs::exists(out.path / "rod_rotor.hpp"));
    const scratch_dir out2("rotor_site_out2");
    check_error_line(run_rotgen("emit rotor_site.yaml --form body -o '" + out2.path.string() + "'",
                                ROTGEN_BINARY_DIR),
                     "rotor_site.yaml:3:3: model 'rod' is a linear rotor (Example 5.4): its form "
                     "is 'rotor' (two angles), not --form body");
    CHECK(!fs::exists(out2.path));
    // the text report works
    const run_result r = run_rotgen("inspect rotor_site.yaml --inertia", ROTGEN_BINARY_DIR);
    CHECK(r.status == 0);
    CHECK(contains(r.out, "  I2 = 6  along "));
    CHECK(contains(r.out, "class: rotor"));
}

TEST_CASE("rotor: zero moments that are not a rotor are refused", "[inertia][rotor][errors]") {
    using row = std::tuple<std::string, std::string>;
    auto [text, line] = GENERATE(table<std::string, std::string>({
        row{"name: b\nbody:\n  parts:\n    - point: {mass: 1, at: [0, 0, 0]}\n",
            "rotor_bad.yaml:3:3: the inertia of 'body' has every principal moment zero (0, 0, 0): "
            "a point at the fixed point has no rotation to describe"},
        row{"name: b\ninertia: [1e-20, 1, 1]\n",
            "rotor_bad.yaml:2:10: inertia has a principal moment that is zero to double "
            "precision (1e-20, 1, 1) but not exactly; a body on a line (a linear rotor, Example "
            "5.4) has I1 = 0 exactly: give its moments exactly"},
    }));
    const scratch_file file("rotor_bad.yaml", text);
    check_error_line(run_rotgen("inspect rotor_bad.yaml --inertia", ROTGEN_BINARY_DIR), line);
}
