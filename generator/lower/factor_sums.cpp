// rotgen — lowering: sums. Terms that differ only in parameters combined into one fraction,
// greedy Horner factoring, flattening of overlapping sums, plain sums with a positive leading
// term. The rules are in lower.hpp.
#include "lower/detail.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace rotgen::lowering {

using GiNaC::ex_to;
using GiNaC::is_a;

namespace {

// True if every number in e is an exact rational (no float that GiNaC did not parse from text).
bool is_exact(const ex& e) {
    if (is_a<numeric>(e)) return ex_to<numeric>(e).is_rational();
    for (std::size_t i = 0; i < e.nops(); ++i)
        if (!is_exact(e.op(i))) return false;
    return true;
}

} // namespace

// Terms with the same state-dependent factors become one term, the sum of their parameter
// coefficients brought to a single fraction by normal(): x y/I1 - x y/I2 -> x y (I2 - I1)/(I1
// I2). A difference of rounded reciprocals has no accurate digits left when I1 ~ I2; I2 - I1
// of two inputs is exact. The constant k joins the terms with no state-dependent factor.
// (Horner's factoring below never makes such a sum again: it divides terms by common
// factors, which keeps their state-dependent parts distinct.)
void dag_builder::combine_parameters(std::vector<poly_term>& terms, numeric& k) {
    std::map<monomial, std::vector<std::size_t>> groups; // state part -> terms
    for (std::size_t i = 0; i < terms.size(); ++i)
        groups[state_part(terms[i].m)].push_back(i);
    if (groups.size() == terms.size() && (k.is_zero() || !groups.count({}))) return;
    std::vector<poly_term> combined;
    numeric constant = k;
    for (const auto& [state, members] : groups) {
        const bool with_k = state.empty() && !k.is_zero();
        ex coefficient = with_k ? ex(k) : ex(0);
        for (std::size_t i : members)
            coefficient += terms[i].c * parameter_part(terms[i].m);
        if (members.size() + (with_k ? 1 : 0) < 2 || !is_exact(coefficient)) {
            for (std::size_t i : members)
                combined.push_back(terms[i]);
            continue;
        }
        if (with_k) constant -= k;
        const auto [n, d] = single_fraction(coefficient);
        const linear num = convert_normal(n);
        const linear den = convert_normal(d);
        if (num.node < 0 && num.c.is_zero()) continue; // the terms cancel
        poly_term t{num.c / den.c, state};
        if (num.node >= 0) merge(t.m, num.node, 1);
        if (den.node >= 0) merge(t.m, den.node, -1);
        if (t.m.empty())
            constant += t.c;
        else
            combined.push_back(std::move(t));
    }
    terms = std::move(combined);
    k = constant;
}

// c = n/d, expanded, with common factors cancelled by normal(). n and d are unique up to a
// constant factor, fixed here (d has integer coefficients with no common divisor), and up to
// the sign, which the DAG fixes (every sum has its leading term positive): the same program
// every run, though normal()'s own output changes from run to run. Memoised for the process:
// the same few coefficients recur in every sum, output and candidate of a model, and normal()
// is the dearest step of lowering.
std::pair<ex, ex> dag_builder::single_fraction(const ex& c) {
    static std::map<ex, std::pair<ex, ex>, GiNaC::ex_is_less> memo;
    const auto it = memo.find(c);
    if (it != memo.end()) return it->second;
    const ex nd = GiNaC::normal(c).numer_denom();
    const numeric content = nd.op(1).expand().integer_content();
    const std::pair<ex, ex> r{(nd.op(0) / content).expand(), (nd.op(1) / content).expand()};
    memo.emplace(c, r);
    return r;
}

monomial dag_builder::state_part(const monomial& m) const {
    monomial s;
    for (const auto& [b, x] : m)
        if (!m_parametric[static_cast<std::size_t>(b)]) s.emplace(b, x);
    return s;
}

ex dag_builder::parameter_part(const monomial& m) {
    ex r = 1;
    for (const auto& [b, x] : m)
        if (m_parametric[static_cast<std::size_t>(b)]) r *= GiNaC::pow(expression(b), x);
    return r;
}

// Greedy multivariate Horner scheme: pull the factor shared by the most terms out of them,
// recursively (x y + x z + w -> x (y + z) + w). Denominator factors count as factors too
// (a/s + b/s -> (a + b)/s). Ties go to the smaller digest, so the result is deterministic.
linear dag_builder::horner(std::vector<poly_term> terms, numeric k) {
    flatten_overlapping_sums(terms, k);
    std::map<std::pair<int, int>, int> count; // (factor, sign of its exponent) -> terms
    for (const poly_term& t : terms)
        for (const auto& [b, x] : t.m)
            ++count[{b, x > 0 ? 1 : -1}];
    int best = -1, best_sign = 0, best_count = 1;
    for (const auto& [key, n] : count) {
        const bool better =
            n > best_count ||
            (n == best_count && best >= 0 &&
             (before(key.first, best) || (key.first == best && key.second > best_sign)));
        if (n >= 2 && better) best = key.first, best_sign = key.second, best_count = n;
    }
    if (best < 0) return plain_sum(terms, k);
    std::vector<poly_term> with, without;
    long power_of = 0;
    for (poly_term& t : terms) {
        const auto it = t.m.find(best);
        if (it != t.m.end() && (it->second > 0 ? 1 : -1) == best_sign) {
            const long x = std::labs(it->second);
            power_of = power_of == 0 ? x : std::min(power_of, x);
            with.push_back(std::move(t));
        } else {
            without.push_back(std::move(t));
        }
    }
    for (poly_term& t : with) {
        auto it = t.m.find(best);
        it->second -= best_sign * power_of;
        if (it->second == 0) t.m.erase(it);
    }
    const linear inner = horner(std::move(with), 0);
    monomial m;
    if (inner.node >= 0) merge(m, inner.node, 1);
    merge(m, best, best_sign * power_of);
    without.push_back({inner.c, std::move(m)});
    sort_poly(without);
    return horner(std::move(without), k);
}

// A linear combination of sums that have like terms whose coefficients involve parameters,
// or the same term with coefficients that cancel, as one sum: (x + a y) - (x + b y) -> (a - b)
// y, with the coefficients combined as in combine_parameters (not the difference of two nearly
// equal products when a ~ b) and x cancelled exactly. (The factoring above leaves such
// combinations where the expression multiplied sums out: c A - c B -> c (A - B).) Other sums
// stay nodes, computed once for all their uses: flattening sums whose like terms have numeric
// coefficients only (specialised kernels) costs more operations than it saves (+20% on the
// full tensor's).
void dag_builder::flatten_overlapping_sums(std::vector<poly_term>& terms, numeric& k) {
    const auto sum_of = [&](const poly_term& t) -> const lowered_node* {
        if (t.m.size() != 1 || t.m.begin()->second != 1) return nullptr;
        const lowered_node& n = m_p.nodes[static_cast<std::size_t>(t.m.begin()->first)];
        return n.k == lowered_node::kind::sum ? &n : nullptr;
    };
    // Every term the sums would contribute, grouped by its state-dependent part (like terms)
    // and by its whole monomial (the same term): which of `terms` it comes from, whether a
    // parameter is involved, the total coefficient.
    struct group {
        std::set<std::size_t> from;
        bool parametric = false;
        numeric total = 0;
    };
    std::map<monomial, group> like, same;
    const auto add = [&](const monomial& m, const numeric& c, std::size_t i) {
        const monomial state = state_part(m);
        group& l = like[state];
        l.from.insert(i);
        l.parametric = l.parametric || state.size() != m.size();
        group& s = same[m];
        s.from.insert(i);
        s.total += c;
    };
    bool any = false;
    for (std::size_t i = 0; i < terms.size(); ++i) {
        const lowered_node* s = sum_of(terms[i]);
        if (!s) {
            add(terms[i].m, terms[i].c, i);
            continue;
        }
        any = true;
        if (!s->value.is_zero()) add({}, terms[i].c * s->value, i);
        for (const auto& [c, id] : s->terms)
            add(monomial_of(id), terms[i].c * c, i);
    }
    if (!any) return;
    if (!k.is_zero()) add({}, k, terms.size());
    std::set<std::size_t> flatten;
    const auto mark = [&](const group& g) {
        for (std::size_t i : g.from)
            if (i < terms.size() && sum_of(terms[i])) flatten.insert(i);
    };
    for (const auto& [state, g] : like)
        if (g.from.size() > 1 && g.parametric) mark(g);
    for (const auto& [m, g] : same)
        if (g.from.size() > 1 && g.total.is_zero()) mark(g);
    if (flatten.empty()) return;
    std::map<monomial, numeric> acc;
    for (std::size_t i = 0; i < terms.size(); ++i) {
        if (!flatten.count(i)) {
            acc[terms[i].m] += terms[i].c;
            continue;
        }
        const lowered_node s = *sum_of(terms[i]);
        k += terms[i].c * s.value;
        for (const auto& [c, id] : s.terms)
            acc[monomial_of(id)] += terms[i].c * c;
    }
    terms.clear();
    for (const auto& [m, c] : acc)
        if (!c.is_zero()) terms.push_back({c, m});
    combine_parameters(terms, k);
    sort_poly(terms);
}

// A sum with no factor to pull out: leading term positive, a common numeric factor outside
// when that saves multiplications.
linear dag_builder::plain_sum(const std::vector<poly_term>& poly, const numeric& k) {
    std::map<int, numeric> acc;
    numeric constant = k;
    for (const poly_term& t : poly) {
        const linear v = from_monomial(t.c, t.m);
        if (v.node < 0)
            constant += v.c;
        else
            acc[v.node] += v.c;
    }
    std::vector<std::pair<numeric, int>> terms;
    for (const auto& [node, c] : acc)
        if (!c.is_zero()) terms.emplace_back(c, node);
    if (terms.empty()) return {constant, -1};
    if (terms.size() == 1 && constant.is_zero()) return {terms[0].first, terms[0].second};
    sort_terms(terms);
    numeric scale = terms[0].first.is_negative() ? -1 : 1; // leading term positive
    if (all_rational(terms, constant)) {
        numeric num = 0, den = 1;
        for (const auto& t : terms)
            num = GiNaC::gcd(num, t.first.numer()), den = GiNaC::lcm(den, t.first.denom());
        if (!constant.is_zero())
            num = GiNaC::gcd(num, constant.numer()), den = GiNaC::lcm(den, constant.denom());
        const numeric content = num / den;
        std::size_t cost_now = 0, cost_then = 1;
        for (const auto& t : terms) {
            cost_now += abs(t.first).is_equal(1) ? 0 : 1;
            cost_then += abs(t.first / content).is_equal(1) ? 0 : 1;
        }
        if (cost_then < cost_now) scale *= content;
    }
    for (auto& t : terms)
        t.first = t.first / scale;
    return {scale, sum(std::move(terms), constant / scale)};
}

bool dag_builder::all_rational(const std::vector<std::pair<numeric, int>>& terms,
                               const numeric& k) {
    for (const auto& t : terms)
        if (!t.first.is_rational()) return false;
    return k.is_rational();
}

void dag_builder::sort_poly(std::vector<poly_term>& v) const {
    // by the digests of the factors, then their exponents: a content order
    std::sort(v.begin(), v.end(),
              [&](const poly_term& a, const poly_term& b) { return key_of(a) < key_of(b); });
}

std::vector<std::pair<std::uint64_t, long>> dag_builder::key_of(const poly_term& t) const {
    std::vector<std::pair<std::uint64_t, long>> k;
    for (const auto& [b, x] : t.m)
        k.emplace_back(digest(b), x);
    std::sort(k.begin(), k.end());
    return k;
}

} // namespace rotgen::lowering
