// rotgen — lowering: operation counts. Of GiNaC expressions printed naively (the "before" of a
// header's operation counts) and of a lowered program as the emitter prints it (the "after").
#include "lower/detail.hpp"

#include <stdexcept>

namespace rotgen {

using GiNaC::ex_to;
using GiNaC::is_a;
using namespace lowering;

namespace {

// ---- naive operation counts of GiNaC expressions (tree size; memoised on the DAG) ----

class naive_counter {
  public:
    op_count operator()(const ex& e) {
        const auto it = m_memo.find(e);
        if (it != m_memo.end()) return it->second;
        op_count r = count(e);
        m_memo.emplace(e, r);
        return r;
    }

  private:
    op_count count(const ex& e) {
        op_count r;
        if (is_a<numeric>(e) || is_a<GiNaC::symbol>(e) || is_a<GiNaC::constant>(e)) return r;
        if (is_a<GiNaC::add>(e)) {
            r.add = e.nops() - 1;
            for (std::size_t i = 0; i < e.nops(); ++i)
                r += (*this)(e.op(i));
            return r;
        }
        if (is_a<GiNaC::mul>(e) || is_a<GiNaC::power>(e)) {
            std::size_t num = 0, den = 0;
            const auto factor = [&](const ex& f) {
                if (is_a<numeric>(f)) {
                    if (!abs(ex_to<numeric>(f)).is_equal(1)) ++num;
                    return;
                }
                if (is_a<GiNaC::power>(f) && is_a<numeric>(f.op(1)) &&
                    ex_to<numeric>(f.op(1)).is_integer()) {
                    const long k = ex_to<numeric>(f.op(1)).to_long();
                    r.mul += static_cast<std::size_t>(std::labs(k) - 1);
                    ++(k > 0 ? num : den);
                    r += (*this)(f.op(0));
                    return;
                }
                if (is_a<GiNaC::power>(f)) {
                    r.call += 1;
                    ++num;
                    r += (*this)(f.op(0));
                    r += (*this)(f.op(1));
                    return;
                }
                ++num;
                r += (*this)(f);
            };
            if (is_a<GiNaC::mul>(e))
                for (std::size_t i = 0; i < e.nops(); ++i)
                    factor(e.op(i));
            else
                factor(e);
            if (num > 1) r.mul += num - 1;
            if (den > 0) r.div += 1, r.mul += den - 1;
            return r;
        }
        if (is_a<GiNaC::function>(e)) {
            r.call = 1;
            for (std::size_t i = 0; i < e.nops(); ++i)
                r += (*this)(e.op(i));
            return r;
        }
        return r;
    }

    std::map<ex, op_count, GiNaC::ex_is_less> m_memo;
};

// Mirrors program_printer (emit/printer.cpp) choice for choice, counting instead of printing:
// which products print flattened into their parent, which sums take a number multiplied in, where
// a negation is absorbed, and the unary minus of a sum whose terms are all negative.
class printed_counter {
  public:
    explicit printed_counter(const lowered_program& p) : m_p(p) {}

    // The node as used by a parent: a temporary or input by name (no operation), else inline.
    op_count ref(int id) const {
        if (m_p.temporary_name.count(id) || node(id).k == lowered_node::kind::input) return {};
        return definition(id);
    }

    // The node's own expression (children by reference).
    op_count definition(int id) const {
        const lowered_node& n = node(id);
        switch (n.k) {
        case lowered_node::kind::input:
        case lowered_node::kind::number: // a literal: folded by the compiler
        case lowered_node::kind::constant:
            return {};
        case lowered_node::kind::sum:
            return sum(n, 1);
        case lowered_node::kind::product:
            return product(n, 1);
        case lowered_node::kind::call: {
            op_count r;
            r.call = 1;
            for (int a : n.args)
                r += ref(a);
            return r;
        }
        }
        throw std::logic_error("lower: unknown node kind");
    }

  private:
    const lowered_node& node(int id) const { return m_p.nodes.at(static_cast<std::size_t>(id)); }

    bool inline_product(int id) const {
        return node(id).k == lowered_node::kind::product && !m_p.temporary_name.count(id);
    }

    bool inline_sum(int id) const {
        return node(id).k == lowered_node::kind::sum && !m_p.temporary_name.count(id);
    }

    bool parameter_quotient(int id) const {
        const lowered_node& n = node(id);
        return n.k == lowered_node::kind::product && !n.numerator.empty() &&
               !n.denominator.empty() && m_p.parametric.at(static_cast<std::size_t>(id));
    }

    // The factors of an inline product, flattened: `num` and `den` count those above and below
    // the bar.
    void factors(int id, bool above, std::size_t& num, std::size_t& den, op_count& ops,
                 bool* negate = nullptr) const {
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
            ops += sum(node(id), -1);
            ++num;
            return;
        }
        if (negate && *negate && above && inline_product(id)) { // a parameter quotient
            ops += product(node(id), 1, negate);
            ++num;
            return;
        }
        ops += ref(id);
        ++(above ? num : den);
    }

    // coef a0 a1 ... / (b0 b1 ...): a multiplication between factors, one for a coefficient
    // other than 1, one division for the whole denominator.
    op_count product(const lowered_node& n, const numeric& coef, bool* negate = nullptr) const {
        std::size_t num = 0, den = 0;
        op_count r;
        for (int c : n.numerator)
            factors(c, true, num, den, r, negate);
        for (int c : n.denominator)
            factors(c, false, num, den, r);
        if (num > 1) r.mul += num - 1;
        if (!coef.is_equal(1) && num > 0) r.mul += 1;
        if (den > 0) r.div += 1, r.mul += den - 1;
        return r;
    }

    static bool flattening_pays(const numeric& c, const lowered_node& inner) {
        std::size_t now = abs(c).is_equal(1) ? 0 : 1, then = 0;
        for (const auto& t : inner.terms) {
            now += abs(t.first).is_equal(1) ? 0 : 1;
            then += abs(c * t.first).is_equal(1) ? 0 : 1;
        }
        return then <= now;
    }

    // The terms of `n` times `scale`: `terms` and `positive` count them.
    void sum_entries(const lowered_node& n, const numeric& scale, std::size_t& terms,
                     std::size_t& positive, numeric& constant, op_count& ops) const {
        constant += scale * n.value;
        for (const auto& [c0, id] : n.terms) {
            const numeric c = scale * c0;
            if (inline_sum(id) && flattening_pays(c, node(id))) {
                sum_entries(node(id), c, terms, positive, constant, ops);
                continue;
            }
            const numeric m = abs(c);
            if (inline_product(id)) {
                ops += product(node(id), m);
            } else {
                ops += ref(id);
                if (!m.is_equal(1)) ops.mul += 1;
            }
            ++terms;
            positive += c.is_negative() ? 0 : 1;
        }
    }

    // Additions between terms, and a unary minus when every term is negative.
    op_count sum(const lowered_node& n, const numeric& scale) const {
        if (n.terms.size() == 1 && n.value.is_zero() && (scale * n.terms[0].first).is_negative() &&
            inline_product(n.terms[0].second)) {
            bool negate = true;
            const op_count p =
                product(node(n.terms[0].second), abs(scale * n.terms[0].first), &negate);
            if (!negate) return p;
        }
        op_count r;
        std::size_t terms = 0, positive = 0;
        numeric constant = 0;
        sum_entries(n, scale, terms, positive, constant, r);
        if (!constant.is_zero() || terms == 0) {
            ++terms;
            positive += constant.is_negative() ? 0 : 1;
        }
        r.add += terms - 1 + (positive == 0 ? 1 : 0);
        return r;
    }

    const lowered_program& m_p;
};

} // namespace

op_count count_ops(const ex& e) {
    return naive_counter()(e);
}

op_count lowering::naive_ops(const std::vector<ex>& outputs) {
    naive_counter naive;
    op_count r;
    for (const ex& e : outputs)
        r += naive(e);
    return r;
}

op_count lowering::printed_ops(const lowered_program& p) {
    const printed_counter counter(p);
    op_count r;
    for (const auto& s : p.steps)
        r += counter.definition(s.node);
    for (int o : p.outputs)
        r += counter.ref(o);
    return r;
}

} // namespace rotgen
