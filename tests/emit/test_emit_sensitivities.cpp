// `rotgen emit --sensitivities`: the keys it refuses (one line, exit 2, nothing written), the two
// functions it adds and documents, and its determinism. The kernels' values are checked in
// tests/kernels/test_emit_sensitivities.cpp.
#include "emit_support.hpp"
#include "error_sites.hpp"
#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <tuple>

using namespace rotgen;
using namespace rotgen::test;
using Catch::Matchers::Contains;

namespace {

std::string sq(const std::filesystem::path& p) {
    return "'" + p.string() + "'";
}

} // namespace

TEST_CASE("emit --sensitivities refuses bad keys in one line and writes nothing",
          "[emit][sensitivities][errors]") {
    scratch_dir dir("tests_tmp_emit_sensitivity_errors");
    const std::string emit = "emit " + sq(model_path("heavy_top")) + " -o " + sq(dir.path);
    using row = std::tuple<std::string, std::string>;
    // arguments after the model and -o, the whole message line
    const auto [args, line] = GENERATE_COPY(table<std::string, std::string>({
        row{" --sensitivities parameters.hh",
            "rotgen emit: --sensitivities: 'parameters.hh': model 'heavy_top' has no parameter "
            "'hh'; did you mean 'parameters.h'?"},
        row{" --sensitivities initial.theta",
            "rotgen emit: --sensitivities: 'initial.theta' is not a parameter key (emit takes "
            "parameters.<name>)"},
        row{" --sensitivities parameters.h,parameters.I3 --specialise=I3,g",
            "rotgen emit: --sensitivities: 'parameters.I3' is folded into the code by "
            "--specialise; leave I3 out of --specialise"},
        row{" --sensitivities parameters.h --specialise",
            "rotgen emit: --sensitivities: 'parameters.h' is folded into the code by "
            "--specialise; leave h out of --specialise"},
        row{" --sensitivities parameters.h,parameters.M,parameters.h",
            "rotgen emit: --sensitivities: 'parameters.h' given twice"},
        row{" --form reduced --sensitivities parameters.p_psi",
            "rotgen emit: --sensitivities: 'parameters.p_psi': model 'heavy_top' has no "
            "parameter 'p_psi'"},
        row{" --outputs rhs,taylor --sensitivities parameters.h",
            "rotgen emit: --sensitivities: no Taylor recurrences for the variational equations "
            "yet; leave taylor out of --outputs"},
        row{" --sensitivities parameters.h,,parameters.M",
            "rotgen emit: --sensitivities: empty name in 'parameters.h,,parameters.M'"},
    }));
    INFO(args);
    check_error_line(run_rotgen(emit + args), line);
    CHECK(!std::filesystem::exists(dir.path));
}

TEST_CASE("emit --sensitivities adds parameter_jacobian and variational_rhs, documented",
          "[emit][sensitivities]") {
    const model_spec spec = load_model(model_path("heavy_top"));
    const derivation d = derive(spec);
    emit_request o;
    o.outputs = {"rhs", "jacobian"};
    const std::string plain = emit_with(spec, d, o).text;
    CHECK_THAT(plain, !Contains("parameter_jacobian") && !Contains("variational_rhs") &&
                          !Contains("sensitivity"));
    o.sensitivities = {"parameters.h", "parameters.I3", "parameters.M"};
    for (const form_kind form :
         {form_kind::lagrangian, form_kind::hamiltonian, form_kind::reduced, form_kind::body}) {
        o.form = form;
        const std::string t = emit_with(spec, d, o).text;
        INFO(to_string(form));
        CHECK_THAT(t, Contains("constexpr std::size_t sensitivity_count = 3;"));
        CHECK_THAT(t, Contains("sensitivity_names{{\"h\", \"I3\", \"M\"}}"));
        CHECK_THAT(t, Contains("void parameter_jacobian(T t, const T* y, T* dfdp, "
                               "const prepared<T>& p) {"));
        CHECK_THAT(t, Contains("void variational_rhs(T t, const T* y, const T* S, T* dydt, "
                               "T* dSdt, const prepared<T>& p) {"));
        CHECK_THAT(t, Contains("///   dy/dt = f(t, y),   dS/dt = (d f/dy) S + [0 | d f/dp],"));
        CHECK_THAT(t, Contains("/// \\param dfdp  output, dim ") &&
                          Contains(" x 3 (row-major), columns (h, I3, M)"));
        CHECK_THAT(t, Contains("/// \\param dSdt  output, dim "));
        // the locals of f's derivatives, and the product with S
        CHECK_THAT(t, Contains("const T dfdp_") && Contains("const T dfdy_") && Contains(" * S[") &&
                          Contains("    dSdt["));
        // the model's Jacobian still as without --sensitivities
        if (form == form_kind::lagrangian) {
            const std::size_t a = plain.find("void rhs(T t"), b = t.find("void rhs(T t");
            CHECK(plain.substr(a, plain.find("\n}\n", a) - a) ==
                  t.substr(b, t.find("\n}\n", b) - b));
        }
    }
}

TEST_CASE("emit --sensitivities gives the same bytes twice and regenerates from its command",
          "[emit][sensitivities][determinism]") {
    scratch_dir a("tests_tmp_emit_sens_a"), b("tests_tmp_emit_sens_b");
    for (const std::string form : {"lagrangian", "hamiltonian", "body"}) {
        const std::string args = "emit " + sq(model_path("full_tensor_top")) + " --form " + form +
                                 " --sensitivities parameters.Ixy,parameters.M -o ";
        REQUIRE(run_rotgen(args + sq(a.path)).status == 0);
        REQUIRE(run_rotgen(args + sq(b.path)).status == 0);
    }
    const std::vector<emitted_pair> pairs = emitted_pairs(a.path.string(), b.path.string());
    for (const emitted_pair& h : pairs) {
        INFO(h.name);
        CHECK(h.first == h.second);
        CHECK_THAT(h.first, Contains("--sensitivities parameters.Ixy,parameters.M\n"));
    }
    CHECK(pairs.size() == 3);
    // the command in the header writes it again
    const std::string first = read_file((a.path / "full_tensor_top_body.hpp").string());
    const std::string marker = "regenerate with\n//   rotgen ";
    const std::size_t at = first.find(marker) + marker.size();
    std::filesystem::remove(a.path / "full_tensor_top_body.hpp");
    REQUIRE(run_rotgen(first.substr(at, first.find('\n', at) - at)).status == 0);
    CHECK(read_file((a.path / "full_tensor_top_body.hpp").string()) == first);
}

TEST_CASE("emit --sensitivities in the rotor form: the free rotor's rates do not depend on its "
          "masses and lengths",
          "[emit][sensitivities]") {
    const run_result r = run_rotgen("emit " + sq(model_path("dumbbell")) +
                                    " -o - --sensitivities parameters.m1,parameters.r2");
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Contains("constexpr std::size_t state_size = 4;") &&
                          Contains("void variational_rhs(T t, const T* y, const T* S, T* dydt"));
    // q_ddot = M^{-1} f with M and f both proportional to the moment of inertia: d f/d p = 0,
    // all 4 x 2 entries, and variational_rhs has no d f/d p term
    const std::string zero = " = T(S(0));\n";
    std::size_t zeros = 0;
    for (std::size_t at = r.out.find("    dfdp["); at != std::string::npos;
         at = r.out.find("    dfdp[", at + 1))
        zeros += r.out.compare(r.out.find(" = ", at), zero.size(), zero) == 0;
    CHECK(zeros == 8);
    CHECK_THAT(r.out, !Contains("const T dfdp_"));
}
