// The printer of lowered programs (emit/printer.hpp): its normal print (temporaries, sin/cos
// hoisted) and its inline print (every node at its use) are read back by GiNaC's parser and must
// give the numbers of the expressions they were lowered from.
#include "support.hpp"

#include "derive/derive.hpp"
#include "emit/printer.hpp"
#include "forms/forms.hpp"
#include "lower/lower.hpp"
#include "spec/spec.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

using namespace rotgen;
using namespace rotgen::test;
using Catch::Matchers::Contains;

namespace {

// Printed C++ as GiNaC reads it: literals S(p)/S(q) -> (p)/(q), a number output T(x) -> (x).
GiNaC::ex read_back(std::string text, const GiNaC::symtab& table) {
    for (const char* cast : {"S(", "T("})
        for (std::size_t at = text.find(cast); at != std::string::npos; at = text.find(cast, at))
            text.erase(at, 1);
    GiNaC::parser reader(table, true);
    return reader(text);
}

struct lowered_rates {
    form_expressions f;
    lowered_program program;
    GiNaC::symtab inputs; // name -> symbol
    GiNaC::exmap point;   // symbol -> a number
};

lowered_rates lower_rates(const std::string& model, form_kind form) {
    const model_spec spec = load_model(model_path(model));
    lowered_rates r{
        build_form(spec, derive(spec), form, lagrangian_strategy::explicit_inverse, false),
        {},
        {},
        {}};
    std::vector<program_input> inputs;
    int k = 0;
    const auto add = [&](const GiNaC::ex& symbol, const std::string& name, bool parameter) {
        inputs.push_back({symbol, name, "", parameter});
        r.inputs[name] = symbol;
        r.point[symbol] = GiNaC::numeric(37 + 11 * k++, 41); // 0.9, 1.17, ...
    };
    for (const auto& s : r.f.state)
        add(s.symbol, s.name, false);
    for (const auto& p : r.f.parameters)
        add(p.symbol, p.name, p.specialisable);
    add(r.f.time, "t", false);
    r.program = lower(r.f.rates, inputs);
    return r;
}

double number_at(const GiNaC::ex& e, const GiNaC::exmap& point) {
    return GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(e.subs(point))).to_double();
}

} // namespace

TEST_CASE("the inline print gives the numbers of the normal print and of GiNaC",
          "[emit][printer]") {
    const auto [model, form] =
        GENERATE(table<std::string, form_kind>({{"heavy_top", form_kind::lagrangian},
                                                {"full_tensor_top", form_kind::lagrangian},
                                                {"full_tensor_top", form_kind::hamiltonian},
                                                {"heavy_top", form_kind::body}}));
    INFO(model << ", " << to_string(form));
    const lowered_rates r = lower_rates(model, form);
    const lowered_program& p = r.program;
    REQUIRE_FALSE(p.steps.empty()); // the normal print has temporaries to lose

    // The normal print: each temporary read back into the table, then the outputs.
    GiNaC::symtab with_steps = r.inputs;
    for (const auto& s : p.steps)
        with_steps[s.name] = read_back(print_definition(p, s.node), with_steps);
    std::vector<std::string> targets;
    for (std::size_t i = 0; i < p.outputs.size(); ++i)
        targets.push_back("out" + std::to_string(i));
    const std::string inline_text = print_outputs_inline(p, targets, "S", "");
    CHECK(inline_text.find("sin_") == std::string::npos);
    CHECK(inline_text.find("t000") == std::string::npos);
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < p.outputs.size(); ++i) {
        const std::size_t end = inline_text.find(";\n", line_start);
        REQUIRE(end != std::string::npos);
        const std::string line = inline_text.substr(line_start, end - line_start);
        line_start = end + 2;
        const std::string lhs = targets[i] + " = ";
        REQUIRE(line.rfind(lhs, 0) == 0);
        const double exact = number_at(r.f.rates[i], r.point);
        const double normal =
            number_at(read_back(print_node(p, p.outputs[i]), with_steps), r.point);
        const double all_inline = number_at(read_back(line.substr(lhs.size()), r.inputs), r.point);
        INFO("output " << i << ": " << line);
        CHECK_THAT(normal, Catch::Matchers::WithinRel(exact, 1e-12) ||
                               Catch::Matchers::WithinAbs(exact, 1e-12));
        CHECK_THAT(all_inline, Catch::Matchers::WithinRel(exact, 1e-12) ||
                                   Catch::Matchers::WithinAbs(exact, 1e-12));
    }
}

TEST_CASE("print_rhs_inline writes dydt[i] in y[i], p.<name> and t", "[emit][printer]") {
    const model_spec spec = load_model(model_path("heavy_top"));
    const form_expressions f = build_form(spec, derive(spec), form_kind::lagrangian,
                                          lagrangian_strategy::explicit_inverse, false);
    const std::string text = print_rhs_inline(f);
    for (std::size_t i = 0; i < f.state.size(); ++i)
        CHECK_THAT(text, Contains("    dydt[" + std::to_string(i) + "] = "));
    CHECK_THAT(text, Contains("sin(y[1])"));
    CHECK_THAT(text, Contains("p.I1"));
    CHECK(text.find("theta") == std::string::npos);
    CHECK(text.find("const T") == std::string::npos); // no temporaries
    // Folded parameters are numbers: no p.I1 left.
    GiNaC::exmap folded;
    for (const auto& p : f.parameters)
        if (p.name == "I1") folded[p.symbol] = GiNaC::numeric(3, 2);
    CHECK(print_rhs_inline(f, folded).find("p.I1") == std::string::npos);
}

TEST_CASE("lowering's operation counts are those of the printed text", "[emit][printer]") {
    const auto form = GENERATE(form_kind::lagrangian, form_kind::hamiltonian, form_kind::body);
    const lowered_rates r = lower_rates("full_tensor_top", form);
    const op_count printed = printed_op_count(r.program);
    CHECK(printed.add == r.program.after.add);
    CHECK(printed.mul == r.program.after.mul);
    CHECK(printed.div == r.program.after.div);
    CHECK(printed.call == r.program.after.call);
    CHECK(r.program.after.total() > 0);
}
