// rotgen — emission: the C++ printer of lowered programs (printer.hpp).
#include "emit/printer.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace rotgen {

using GiNaC::numeric;

namespace {

std::string numeric_text(const numeric& n) {
    std::ostringstream os;
    os << n;
    return os.str();
}

struct printed {
    std::string text;
    op_count ops;
    bool atomic = true; // needs no parentheses as a factor
};

std::string integer_literal(const numeric& n, const std::string& S) {
    // Exact in every scalar type that can hold it; beyond 64 bits a long double literal.
    const numeric limit = numeric(2).power(62);
    if (abs(n) < limit) return S + "(" + numeric_text(n) + ")";
    return S + "(" + numeric_text(n) + ".0L)";
}

// A non-negative number as a C++ expression: S(p) or S(p)/S(q) (folded by the compiler).
std::string number_literal(const numeric& n, const std::string& S) {
    if (n.is_integer()) return integer_literal(n, S);
    if (n.is_rational()) return integer_literal(n.numer(), S) + "/" + integer_literal(n.denom(), S);
    // An inexact float (not produced by rotgen's parser): as many digits as a long double holds.
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.21Lg", static_cast<long double>(n.to_double()));
    std::string s = buf;
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return S + "(" + s + "L)";
}

class program_printer {
  public:
    program_printer(const lowered_program& p, std::string scalar)
        : m_p(p), m_S(std::move(scalar)) {}

    // The node as used by a parent: a temporary or input by name, else inline.
    printed ref(int id) const {
        const lowered_node& n = node(id);
        const auto t = m_p.temporary_name.find(id);
        if (t != m_p.temporary_name.end()) return {t->second, {}, true};
        if (n.k == lowered_node::kind::input) return {n.name, {}, true};
        return definition(id);
    }

    // The node's own expression (children by reference).
    printed definition(int id) const {
        const lowered_node& n = node(id);
        switch (n.k) {
        case lowered_node::kind::input:
            return {n.name, {}, true};
        case lowered_node::kind::number: {
            // A literal, negative or a fraction, is a constant expression the compiler folds:
            // no operation at run time.
            const std::string lit = number_literal(abs(n.value), m_S);
            if (n.value.is_negative()) return {"-" + lit, {}, false};
            return {lit, {}, n.value.is_integer()};
        }
        case lowered_node::kind::constant:
            return {m_S + "(3.141592653589793238462643383279502884L)", {}, true};
        case lowered_node::kind::sum:
            return sum(n);
        case lowered_node::kind::product:
            return product(n, 1);
        case lowered_node::kind::call: {
            printed r;
            r.text = n.name + "(";
            r.ops.call = 1;
            for (std::size_t i = 0; i < n.args.size(); ++i) {
                const printed a = ref(n.args[i]);
                r.text += (i ? ", " : "") + a.text;
                r.ops += a.ops;
            }
            r.text += ")";
            return r;
        }
        }
        throw std::logic_error("emit: unknown node kind");
    }

  private:
    const lowered_node& node(int id) const { return m_p.nodes.at(static_cast<std::size_t>(id)); }

    bool inline_product(int id) const {
        return node(id).k == lowered_node::kind::product && !m_p.temporary_name.count(id);
    }

    static std::string paren(const printed& p) { return p.atomic ? p.text : "(" + p.text + ")"; }

    // A quotient of parameters alone, (I3 - I1)/I2: printed as one factor, never spread over the
    // product that uses it (it is computed apart from the state).
    bool parameter_quotient(int id) const {
        const lowered_node& n = node(id);
        return n.k == lowered_node::kind::product && !n.numerator.empty() &&
               !n.denominator.empty() && m_p.parametric.at(static_cast<std::size_t>(id));
    }

    // Flattens inline products into one list of factors above and one below the bar.
    // `negate`: if set, the first inline sum above the bar is printed negated (-(a - b) x ->
    // (b - a) x), and `negate` is cleared.
    void factors(int id, bool above, std::vector<std::string>& num, std::vector<std::string>& den,
                 op_count& ops, bool* negate = nullptr) const {
        if (inline_product(id) && !parameter_quotient(id)) {
            const lowered_node& n = node(id);
            for (int c : n.numerator)
                factors(c, above, num, den, ops, negate);
            for (int c : n.denominator)
                factors(c, !above, num, den, ops);
            return;
        }
        if (negate && *negate && above && inline_sum(id)) {
            *negate = false;
            const printed f = sum(node(id), -1);
            ops += f.ops;
            num.push_back(paren(f));
            return;
        }
        if (negate && *negate && above && inline_product(id)) { // a parameter quotient
            printed f = product(node(id), 1, negate);
            ops += f.ops;
            num.push_back(paren(f));
            return;
        }
        const printed f = ref(id);
        ops += f.ops;
        (above ? num : den).push_back(paren(f));
    }

    // coefficient * product, the coefficient a non-negative number (1: none).
    printed product(const lowered_node& n, const numeric& coef, bool* negate = nullptr) const {
        std::vector<std::string> num, den;
        printed r;
        for (int c : n.numerator)
            factors(c, true, num, den, r.ops, negate);
        for (int c : n.denominator)
            factors(c, false, num, den, r.ops);
        std::sort(num.begin(), num.end());
        std::sort(den.begin(), den.end());
        const bool has_coef = !coef.is_equal(1);
        std::string s;
        if (has_coef) s = number_literal(coef, m_S);
        for (std::size_t i = 0; i < num.size(); ++i)
            s += (s.empty() ? "" : "*") + num[i];
        if (s.empty()) s = m_S + "(1)";
        if (num.size() > 1) r.ops.mul += num.size() - 1;
        if (has_coef && !num.empty()) r.ops.mul += 1;
        if (!den.empty()) {
            r.ops.div += 1;
            r.ops.mul += den.size() - 1;
            std::string d;
            for (std::size_t i = 0; i < den.size(); ++i)
                d += (i ? "*" : "") + den[i];
            s += "/" + (den.size() > 1 ? "(" + d + ")" : d);
        }
        r.text = s;
        r.atomic = false;
        return r;
    }

    struct entry {
        bool negative;
        std::string text;
    };

    bool inline_sum(int id) const {
        return node(id).k == lowered_node::kind::sum && !m_p.temporary_name.count(id);
    }

    // c (a x + b y) printed as (c a) x + (c b) y when that needs no more multiplications than
    // c (...) (the products c a are exact rationals, folded by the compiler): a negated sum loses
    // its unary minus, and a number times a sum of terms with coefficients one multiplication.
    static bool flattening_pays(const numeric& c, const lowered_node& inner) {
        std::size_t now = abs(c).is_equal(1) ? 0 : 1, then = 0;
        for (const auto& t : inner.terms) {
            now += abs(t.first).is_equal(1) ? 0 : 1;
            then += abs(c * t.first).is_equal(1) ? 0 : 1;
        }
        return then <= now;
    }

    // The terms of `n`, times `scale`, inline sums flattened into them where that pays.
    void sum_entries(const lowered_node& n, const numeric& scale, std::vector<entry>& entries,
                     numeric& constant, op_count& ops) const {
        constant += scale * n.value;
        for (const auto& [c0, id] : n.terms) {
            const numeric c = scale * c0;
            if (inline_sum(id) && flattening_pays(c, node(id))) {
                sum_entries(node(id), c, entries, constant, ops);
                continue;
            }
            const numeric m = abs(c);
            std::string text;
            if (inline_product(id)) {
                const printed p = product(node(id), m);
                ops += p.ops;
                text = p.text;
            } else {
                const printed p = ref(id);
                ops += p.ops;
                if (m.is_equal(1)) {
                    text = p.text; // a term of a sum needs no parentheses unless it is a sum
                    if (!p.atomic && inline_sum(id)) text = "(" + text + ")";
                } else {
                    text = number_literal(m, m_S) + "*" + paren(p);
                    ops.mul += 1;
                }
            }
            entries.push_back({c.is_negative(), text});
        }
    }

    printed sum(const lowered_node& n, const numeric& scale = 1) const {
        std::vector<entry> entries;
        printed r;
        numeric constant = 0;
        // -c P(S): a negated product with an inline sum among its factors negates that sum
        // instead (no unary minus).
        if (n.terms.size() == 1 && n.value.is_zero() && (scale * n.terms[0].first).is_negative() &&
            inline_product(n.terms[0].second)) {
            bool negate = true;
            const printed p =
                product(node(n.terms[0].second), abs(scale * n.terms[0].first), &negate);
            if (!negate) return p;
        }
        sum_entries(n, scale, entries, constant, r.ops);
        if (!constant.is_zero() || entries.empty())
            entries.push_back({constant.is_negative(), number_literal(abs(constant), m_S)});
        // Positive terms first (no unary minus unless all are negative), then by text.
        std::sort(entries.begin(), entries.end(), [](const entry& a, const entry& b) {
            return a.negative != b.negative ? !a.negative : a.text < b.text;
        });
        std::string s;
        for (std::size_t i = 0; i < entries.size(); ++i) {
            if (i == 0)
                s = entries[i].negative ? "-" + entries[i].text : entries[i].text;
            else
                s += (entries[i].negative ? " - " : " + ") + entries[i].text;
        }
        r.ops.add += entries.size() - 1 + (entries[0].negative ? 1 : 0);
        r.text = s;
        r.atomic = false;
        return r;
    }

    const lowered_program& m_p;
    std::string m_S;
};

} // namespace

std::string print_node(const lowered_program& program, int node, const std::string& scalar) {
    return program_printer(program, scalar).ref(node).text;
}

std::string print_number(const numeric& value, const std::string& scalar) {
    const std::string lit = number_literal(abs(value), scalar);
    return value.is_negative() ? "-" + lit : lit;
}

std::string print_definition(const lowered_program& program, int node, const std::string& scalar) {
    return program_printer(program, scalar).definition(node).text;
}

op_count printed_op_count(const lowered_program& program) {
    const program_printer printer(program, "S");
    op_count r;
    for (const auto& s : program.steps)
        r += printer.definition(s.node).ops;
    for (int o : program.outputs)
        r += printer.ref(o).ops;
    return r;
}

op_count definition_op_count(const lowered_program& program, int node) {
    return program_printer(program, "S").definition(node).ops;
}

op_count constants_op_count(const lowered_program& program) {
    op_count r;
    for (const auto& c : program.constants)
        r += definition_op_count(program, c.node);
    return r;
}

std::string print_outputs_inline(const lowered_program& program,
                                 const std::vector<std::string>& targets, const std::string& scalar,
                                 const std::string& indent) {
    if (targets.size() != program.outputs.size())
        throw std::logic_error("emit: " + std::to_string(targets.size()) + " targets for " +
                               std::to_string(program.outputs.size()) + " outputs");
    // The same nodes with no temporaries: every reference prints the node's definition.
    lowered_program all_inline = program;
    all_inline.steps.clear();
    all_inline.temporary_name.clear();
    const program_printer printer(all_inline, scalar);
    std::string text;
    for (std::size_t i = 0; i < program.outputs.size(); ++i) {
        const int o = program.outputs[i];
        std::string v = printer.ref(o).text;
        const auto k = program.nodes[static_cast<std::size_t>(o)].k;
        if (k == lowered_node::kind::number || k == lowered_node::kind::constant)
            v = "T(" + v + ")";
        text += indent + targets[i] + " = " + v + ";\n";
    }
    return text;
}

std::string print_rhs_inline(const form_expressions& f, const GiNaC::exmap& folded,
                             const std::string& scalar) {
    std::vector<program_input> inputs;
    std::vector<std::string> targets;
    for (std::size_t i = 0; i < f.state.size(); ++i) {
        inputs.push_back({f.state[i].symbol, "y[" + std::to_string(i) + "]", ""});
        targets.push_back("dydt[" + std::to_string(i) + "]");
    }
    for (const auto& p : f.parameters)
        if (!folded.count(p.symbol))
            inputs.push_back({p.symbol, "p." + p.name, "", p.specialisable});
    inputs.push_back({f.time, "t", ""});
    std::vector<GiNaC::ex> rates;
    for (const auto& e : f.rates)
        rates.push_back(e.subs(folded));
    return print_outputs_inline(lower(rates, inputs), targets, scalar);
}

} // namespace rotgen
