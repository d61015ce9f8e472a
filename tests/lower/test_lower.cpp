// Lowering: CSE, trig hoisting, powers as products, exact literals, deterministic names; and the
// lowered program computes what the expressions it came from compute.
#include "support.hpp"

#include "emit/printer.hpp"
#include "forms/forms.hpp"
#include "lower/lower.hpp"

#include <catch2/catch.hpp>

using namespace rotgen;
using namespace rotgen::test;
using Catch::Matchers::Contains;
using GiNaC::ex;

namespace {

std::string program_text(const lowered_program& p) {
    std::string s;
    for (const auto& st : p.steps)
        s += st.name + " = " + print_definition(p, st.node) + "\n";
    for (std::size_t i = 0; i < p.outputs.size(); ++i)
        s += "out" + std::to_string(i) + " = " + print_node(p, p.outputs[i]) + "\n";
    return s;
}

struct fixture {
    GiNaC::realsymbol x{"x"}, y{"y"}, z{"z"};
    std::vector<program_input> inputs{{x, "x", ""}, {y, "y", ""}, {z, "z", ""}};
};

// Inputs of a form: state, parameters, t.
std::vector<program_input> form_inputs(const form_expressions& f) {
    std::vector<program_input> in;
    for (const auto& s : f.state)
        in.push_back({s.symbol, s.name, ""});
    for (const auto& p : f.parameters)
        in.push_back({p.symbol, "p." + p.name, ""});
    in.push_back({f.time, "t", ""});
    return in;
}

} // namespace

TEST_CASE("a subexpression used twice is computed once", "[lower]") {
    fixture f;
    const ex shared = f.x + f.y;
    const lowered_program p = lower({GiNaC::sin(shared) * f.z, GiNaC::cos(shared) + f.z}, f.inputs);
    REQUIRE(p.steps.size() == 1);
    CHECK(p.steps[0].name == "t000");
    CHECK(print_definition(p, p.steps[0].node) == "x + y");
    CHECK(print_node(p, p.outputs[0]) == "sin(t000)*z");
    CHECK(print_node(p, p.outputs[1]) == "cos(t000) + z");
}

TEST_CASE("sin and cos of an input are hoisted and named after it", "[lower]") {
    fixture f;
    const lowered_program p =
        lower({GiNaC::sin(f.x) * f.y, GiNaC::pow(GiNaC::sin(f.x), 2) + GiNaC::cos(f.x)}, f.inputs);
    const std::string text = program_text(p);
    CHECK_THAT(text, Contains("sin_x = sin(x)"));
    CHECK_THAT(text, Contains("cos_x = cos(x)"));
    CHECK(text.find("sin(x)") == text.rfind("sin(x)")); // once
}

TEST_CASE("integer powers become shared products, negative ones a division", "[lower]") {
    fixture f;
    const lowered_program p =
        lower({GiNaC::pow(f.x, 2) * f.y, GiNaC::pow(f.x, 3), 1 / GiNaC::pow(f.x, 2)}, f.inputs);
    const std::string text = program_text(p);
    CHECK_THAT(text, Contains("t000 = x*x"));
    CHECK_THAT(text, Contains("out1 = t000*x"));
    CHECK_THAT(text, Contains("out2 = S(1)/t000"));
    CHECK(text.find("pow") == std::string::npos);
}

TEST_CASE("a - b and b - a are one node", "[lower]") {
    fixture f;
    const lowered_program p = lower({(f.x - f.y) * f.z, (f.y - f.x) / f.z}, f.inputs);
    REQUIRE(p.steps.size() == 1);
    CHECK(print_definition(p, p.steps[0].node) == "x - y");
    CHECK(print_node(p, p.outputs[1]) == "-t000/z");
}

TEST_CASE("rationals print as exact literals folded by the compiler", "[lower]") {
    fixture f;
    const lowered_program p =
        lower({f.x / 3 + GiNaC::numeric(5, 7), ex(GiNaC::numeric(-1, 2))}, f.inputs);
    CHECK(print_node(p, p.outputs[0]) == "S(1)/S(3)*x + S(5)/S(7)");
    CHECK(print_node(p, p.outputs[1]) == "-S(1)/S(2)");
    CHECK(print_node(p, p.outputs[0], "double") == "double(1)/double(3)*x + double(5)/double(7)");
}

TEST_CASE("sums are factored: a common factor is taken out once", "[lower]") {
    fixture f;
    const lowered_program p = lower({f.x * f.y + f.x * f.z + f.y * f.z * f.x * f.x}, f.inputs);
    CHECK(p.after.total() < p.before.total());
    CHECK(p.after.mul <= 3);
}

// Two parameters a, b (model constants) beside the state x, y, z.
struct parameter_fixture : fixture {
    GiNaC::realsymbol a{"a"}, b{"b"};
    parameter_fixture() {
        inputs.push_back({a, "p.a", "", true});
        inputs.push_back({b, "p.b", "", true});
    }
};

TEST_CASE("terms that differ only in parameters become one term over one fraction",
          "[lower][precision]") {
    // x y/a - x y/b as a difference of two rounded reciprocals loses every digit when a ~ b;
    // (b - a)/(a b) has a difference of two inputs, exact when a ~ b.
    parameter_fixture f;
    const lowered_program p = lower({f.x * f.y / f.a - f.x * f.y / f.b}, f.inputs);
    CHECK(program_text(p) == "out0 = ((p.b - p.a)/(p.a*p.b))*x*y\n");
    // The constant joins the terms without a state factor: 1 - a/b -> (b - a)/b.
    const lowered_program q = lower({1 - f.a / f.b + f.x}, f.inputs);
    CHECK(program_text(q) == "out0 = x - (p.a - p.b)/p.b\n");
    // The same sums with a, b taken for state are left as they are.
    parameter_fixture g;
    for (auto& in : g.inputs)
        in.parameter = false;
    CHECK(program_text(lower({g.x * g.y / g.a - g.x * g.y / g.b}, g.inputs)) ==
          "out0 = (S(1)/p.a - S(1)/p.b)*x*y\n");
}

TEST_CASE("parameter coefficients that cancel leave no term", "[lower][precision]") {
    parameter_fixture f;
    const lowered_program p =
        lower({f.x / f.a + f.x / f.b - f.x * (f.a + f.b) / (f.a * f.b) + f.y}, f.inputs);
    CHECK(program_text(p) == "out0 = y\n");
}

TEST_CASE("a combination of sums that share terms is one sum, like terms combined",
          "[lower][precision]") {
    // z (x + a y) - z (x + b y): x cancels, and a y - b y is (a - b) y, not the difference of two
    // nearly equal products when a ~ b.
    parameter_fixture f;
    const lowered_program p = lower({f.z * (f.x + f.a * f.y) - f.z * (f.x + f.b * f.y)}, f.inputs);
    CHECK(program_text(p) == "out0 = (p.a - p.b)*y*z\n");
    // Sums that share no like terms stay apart (each may be shared with other outputs); used
    // once, they print as one sum (the negated one without a unary minus).
    const lowered_program q = lower({f.z * (f.x + f.y) - f.z * (f.a * f.x * f.y + f.b)}, f.inputs);
    CHECK(program_text(q) == "out0 = (x + y - p.a*x*y - p.b)*z\n");
    const lowered_program r =
        lower({f.z * (f.x + f.y) - f.z * (f.a * f.x * f.y + f.b), f.x + f.y}, f.inputs);
    CHECK(program_text(r) == "t000 = x + y\nout0 = (t000 - p.a*x*y - p.b)*z\nout1 = t000\n");
}

TEST_CASE("a symbol that is not an input is an internal error", "[lower]") {
    fixture f;
    GiNaC::realsymbol w("w");
    CHECK_THROWS_WITH(lower({f.x + w}, f.inputs), Contains("free symbol 'w'"));
}

TEST_CASE("operation counts", "[lower]") {
    fixture f;
    CHECK(count_ops(f.x * f.y + f.z).total() == 2);
    CHECK(count_ops(GiNaC::pow(f.x, 3)).mul == 2);
    CHECK(count_ops(GiNaC::sin(f.x) / f.y).total() == 2);
}

TEST_CASE("lowering keeps the values of every form's rhs and Jacobian", "[lower]") {
    const long saved = GiNaC::Digits;
    GiNaC::Digits = 30;
    for (const std::string model :
         {"free_asymmetric_top", "heavy_top", "full_tensor_top", "damped_driven_top"}) {
        const model_spec spec = load_model(model_path(model));
        const derivation d = derive(spec);
        for (const form_kind form :
             {form_kind::lagrangian, form_kind::hamiltonian, form_kind::body}) {
            for (const lagrangian_strategy st :
                 {lagrangian_strategy::explicit_inverse, lagrangian_strategy::solve}) {
                if (form != form_kind::lagrangian && st == lagrangian_strategy::solve) continue;
                const form_expressions fe = build_form(spec, d, form, st, true);
                std::vector<ex> all = fe.rates;
                const std::vector<ex> J = jacobian(fe);
                all.insert(all.end(), J.begin(), J.end());
                const std::vector<program_input> in = form_inputs(fe);
                const lowered_program p = lower(all, in);
                INFO(model << " " << to_string(form) << " " << to_string(st));
                CHECK(p.after.total() < p.before.total());
                std::mt19937 rng(17);
                std::uniform_int_distribution<int> draw(300, 2800);
                for (int point = 0; point < 2; ++point) {
                    GiNaC::exmap at;
                    for (const auto& i : in)
                        at[i.symbol] = GiNaC::numeric(draw(rng), 1000);
                    const std::vector<GiNaC::numeric> lowered = evaluate(p, at);
                    for (std::size_t k = 0; k < all.size(); k += (all.size() > 40 ? 3 : 1)) {
                        const ex direct = GiNaC::evalf(all[k].subs(at));
                        REQUIRE(GiNaC::is_a<GiNaC::numeric>(direct));
                        const GiNaC::numeric a = GiNaC::ex_to<GiNaC::numeric>(direct);
                        const GiNaC::numeric diff = abs(a - lowered[k]);
                        CHECK(diff.to_double() <= 1e-22 * std::max(1.0, abs(a).to_double()));
                    }
                }
            }
        }
    }
    GiNaC::Digits = saved;
}

TEST_CASE("lowering is deterministic: the same program text every time", "[lower]") {
    const model_spec spec = load_model(model_path("full_tensor_top"));
    const derivation d = derive(spec);
    const form_expressions f =
        build_form(spec, d, form_kind::hamiltonian, lagrangian_strategy::explicit_inverse, false);
    const std::string first = program_text(lower(f.rates, form_inputs(f)));
    // Rebuilding the expressions (new GiNaC objects, possibly another internal order) changes
    // nothing.
    const derivation d2 = derive(spec);
    const form_expressions f2 =
        build_form(spec, d2, form_kind::hamiltonian, lagrangian_strategy::explicit_inverse, false);
    CHECK(program_text(lower(f2.rates, form_inputs(f2))) == first);
    CHECK_THAT(first, Contains("t000 = "));
}
