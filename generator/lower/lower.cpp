#include "lower/lower.hpp"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

namespace rotgen {

using GiNaC::ex;
using GiNaC::ex_to;
using GiNaC::is_a;
using GiNaC::numeric;

namespace {

// ---- digests: FNV-1a over content only (never GiNaC's hash, never a pointer) ----

constexpr std::uint64_t fnv_offset = 1469598103934665603ULL;
constexpr std::uint64_t fnv_prime = 1099511628211ULL;

void mix(std::uint64_t& h, const std::string& s) {
    for (unsigned char c : s) {
        h ^= c;
        h *= fnv_prime;
    }
    h ^= 0xffu; // separator
    h *= fnv_prime;
}

void mix(std::uint64_t& h, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) {
        h ^= (v >> (8 * i)) & 0xffu;
        h *= fnv_prime;
    }
}

std::string numeric_text(const numeric& n) {
    std::ostringstream os;
    os << n;
    return os.str();
}

// A value as (coefficient, node): node < 0 means the number `c` alone.
struct linear {
    numeric c;
    int node;
};

// A product as factor -> integer exponent (negative: below the bar).
using monomial = std::map<int, long>;
struct poly_term {
    numeric c;
    monomial m;
};

const std::set<std::string>& known_calls() {
    static const std::set<std::string> f{"sin",  "cos",  "tan",  "asin", "acos", "atan", "atan2",
                                         "sinh", "cosh", "tanh", "exp",  "log",  "abs"};
    return f;
}

bool is_identifier(const std::string& s) {
    static const std::regex id("[A-Za-z_][A-Za-z0-9_]*");
    return std::regex_match(s, id);
}

// A call as lowering names it (sqrt and pow included), applied to GiNaC arguments.
ex apply_call(const std::string& name, const std::vector<ex>& a) {
    if (name == "sin") return GiNaC::sin(a.at(0));
    if (name == "cos") return GiNaC::cos(a.at(0));
    if (name == "tan") return GiNaC::tan(a.at(0));
    if (name == "asin") return GiNaC::asin(a.at(0));
    if (name == "acos") return GiNaC::acos(a.at(0));
    if (name == "atan") return GiNaC::atan(a.at(0));
    if (name == "atan2") return GiNaC::atan2(a.at(0), a.at(1));
    if (name == "sinh") return GiNaC::sinh(a.at(0));
    if (name == "cosh") return GiNaC::cosh(a.at(0));
    if (name == "tanh") return GiNaC::tanh(a.at(0));
    if (name == "exp") return GiNaC::exp(a.at(0));
    if (name == "log") return GiNaC::log(a.at(0));
    if (name == "abs") return GiNaC::abs(a.at(0));
    if (name == "sqrt") return GiNaC::sqrt(a.at(0));
    if (name == "pow") return GiNaC::pow(a.at(0), a.at(1));
    throw std::logic_error("lower: cannot evaluate " + name);
}

// The GiNaC expression a node stands for: `input` for an input node, `child(id)` for each child.
template <class Child> ex node_expression(const lowered_node& n, const ex& input, Child child) {
    ex r;
    switch (n.k) {
    case lowered_node::kind::input:
        return input;
    case lowered_node::kind::number:
        return n.value;
    case lowered_node::kind::constant:
        return GiNaC::Pi;
    case lowered_node::kind::sum:
        r = n.value;
        for (const auto& [c, id] : n.terms)
            r += c * child(id);
        return r;
    case lowered_node::kind::product:
        r = 1;
        for (int id : n.numerator)
            r *= child(id);
        for (int id : n.denominator)
            r /= child(id);
        return r;
    case lowered_node::kind::call: {
        std::vector<ex> args;
        for (int id : n.args)
            args.push_back(child(id));
        return apply_call(n.name, args);
    }
    }
    throw std::logic_error("lower: unknown node kind");
}

// True if every number in e is an exact rational (no float that GiNaC did not parse from text).
bool is_exact(const ex& e) {
    if (is_a<numeric>(e)) return ex_to<numeric>(e).is_rational();
    for (std::size_t i = 0; i < e.nops(); ++i)
        if (!is_exact(e.op(i))) return false;
    return true;
}

std::vector<int> children(const lowered_node& n) {
    std::vector<int> c;
    for (const auto& t : n.terms)
        c.push_back(t.second);
    c.insert(c.end(), n.numerator.begin(), n.numerator.end());
    c.insert(c.end(), n.denominator.begin(), n.denominator.end());
    c.insert(c.end(), n.args.begin(), n.args.end());
    return c;
}

// Builds the hash-consed DAG.
class dag_builder {
  public:
    dag_builder(lowered_program& program) : m_p(program) {
        for (std::size_t i = 0; i < m_p.inputs.size(); ++i) {
            const program_input& in = m_p.inputs[i];
            if (!is_a<GiNaC::symbol>(in.symbol))
                throw std::logic_error("lower: input '" + in.name + "' is not a symbol");
            lowered_node n;
            n.k = lowered_node::kind::input;
            n.name = in.name;
            const int id = intern(std::move(n), "I|" + in.name);
            if (!m_input_of.emplace(in.symbol, id).second)
                throw std::logic_error("lower: input '" + in.name + "' given twice");
            m_parametric[static_cast<std::size_t>(id)] = in.parameter;
            m_ex_of.emplace(id, in.symbol);
        }
    }

    int materialize(const linear& v) {
        if (v.node < 0) return number(v.c);
        if (v.c.is_equal(1)) return v.node;
        return sum({{v.c, v.node}}, 0);
    }

    linear convert(const ex& e) {
        const auto it = m_memo.find(e);
        if (it != m_memo.end()) return it->second;
        const linear r = convert_uncached(e);
        m_memo.emplace(e, r);
        return r;
    }

  private:
    linear convert_uncached(const ex& e) {
        if (is_a<numeric>(e)) {
            const numeric& n = ex_to<numeric>(e);
            if (!n.is_real()) throw std::logic_error("lower: complex number " + numeric_text(n));
            return {n, -1};
        }
        if (is_a<GiNaC::symbol>(e)) {
            const auto it = m_input_of.find(e);
            if (it == m_input_of.end())
                throw std::logic_error("lower: free symbol '" + ex_to<GiNaC::symbol>(e).get_name() +
                                       "' (not an input of the program)");
            return {1, it->second};
        }
        if (is_a<GiNaC::constant>(e)) {
            if (!e.is_equal(GiNaC::Pi)) {
                std::ostringstream os;
                os << e;
                throw std::logic_error("lower: unknown constant " + os.str());
            }
            lowered_node n;
            n.k = lowered_node::kind::constant;
            n.name = "pi";
            return {1, intern(std::move(n), "K|pi")};
        }
        if (is_a<GiNaC::add>(e)) return convert_sum(e);
        if (is_a<GiNaC::mul>(e) || is_a<GiNaC::power>(e)) return convert_product(e);
        if (is_a<GiNaC::function>(e)) {
            const std::string name = ex_to<GiNaC::function>(e).get_name();
            if (!known_calls().count(name))
                throw std::logic_error("lower: unsupported function '" + name + "'");
            std::vector<int> args;
            for (std::size_t i = 0; i < e.nops(); ++i)
                args.push_back(materialize(convert(e.op(i))));
            return {1, call(name, args)};
        }
        std::ostringstream os;
        os << e;
        throw std::logic_error("lower: cannot lower expression '" + os.str() + "'");
    }

    // `combine`: false for the numerator or denominator of a fraction normal() has just made.
    linear convert_sum(const ex& e, bool combine = true) {
        std::map<int, numeric> acc;
        numeric k = 0;
        for (std::size_t i = 0; i < e.nops(); ++i) {
            const linear t = convert(e.op(i));
            if (t.node < 0)
                k += t.c;
            else
                acc[t.node] += t.c;
        }
        std::vector<poly_term> terms;
        for (const auto& [node, c] : acc)
            if (!c.is_zero()) terms.push_back({c, monomial_of(node)});
        if (combine) combine_parameters(terms, k);
        sort_poly(terms);
        return horner(std::move(terms), k);
    }

    // Terms with the same state-dependent factors become one term, the sum of their parameter
    // coefficients brought to a single fraction by normal(): x y/I1 - x y/I2 -> x y (I2 - I1)/(I1
    // I2). A difference of rounded reciprocals has no accurate digits left when I1 ~ I2; I2 - I1
    // of two inputs is exact. The constant k joins the terms with no state-dependent factor.
    // (Horner's factoring below never makes such a sum again: it divides terms by common
    // factors, which keeps their state-dependent parts distinct.)
    void combine_parameters(std::vector<poly_term>& terms, numeric& k) {
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
    static std::pair<ex, ex> single_fraction(const ex& c) {
        static std::map<ex, std::pair<ex, ex>, GiNaC::ex_is_less> memo;
        const auto it = memo.find(c);
        if (it != memo.end()) return it->second;
        const ex nd = GiNaC::normal(c).numer_denom();
        const numeric content = nd.op(1).expand().integer_content();
        const std::pair<ex, ex> r{(nd.op(0) / content).expand(), (nd.op(1) / content).expand()};
        memo.emplace(c, r);
        return r;
    }

    // A numerator or denominator from normal(): a sum is converted as it is (it is in normal
    // form already; combining it again would call normal() on it again, for ever).
    linear convert_normal(const ex& e) {
        if (!is_a<GiNaC::add>(e)) return convert(e);
        const auto it = m_memo.find(e);
        if (it != m_memo.end()) return it->second;
        const linear r = convert_sum(e, false);
        m_memo.emplace(e, r);
        return r;
    }

    monomial state_part(const monomial& m) const {
        monomial s;
        for (const auto& [b, x] : m)
            if (!m_parametric[static_cast<std::size_t>(b)]) s.emplace(b, x);
        return s;
    }

    ex parameter_part(const monomial& m) {
        ex r = 1;
        for (const auto& [b, x] : m)
            if (m_parametric[static_cast<std::size_t>(b)]) r *= GiNaC::pow(expression(b), x);
        return r;
    }

    // The GiNaC expression a parameter-only node stands for (inputs are in m_ex_of from the
    // start).
    ex expression(int id) {
        const auto it = m_ex_of.find(id);
        if (it != m_ex_of.end()) return it->second;
        const lowered_node n = m_p.nodes[static_cast<std::size_t>(id)];
        if (n.k == lowered_node::kind::input)
            throw std::logic_error("lower: input '" + n.name + "' without a symbol");
        const ex r = node_expression(n, ex(), [&](int child) { return expression(child); });
        m_ex_of.emplace(id, r);
        return r;
    }

    // Greedy multivariate Horner scheme: pull the factor shared by the most terms out of them,
    // recursively (x y + x z + w -> x (y + z) + w). Denominator factors count as factors too
    // (a/s + b/s -> (a + b)/s). Ties go to the smaller digest, so the result is deterministic.
    linear horner(std::vector<poly_term> terms, numeric k) {
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
    void flatten_overlapping_sums(std::vector<poly_term>& terms, numeric& k) {
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
    linear plain_sum(const std::vector<poly_term>& poly, const numeric& k) {
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

    static bool all_rational(const std::vector<std::pair<numeric, int>>& terms, const numeric& k) {
        for (const auto& t : terms)
            if (!t.first.is_rational()) return false;
        return k.is_rational();
    }

    void sort_poly(std::vector<poly_term>& v) const {
        // by the digests of the factors, then their exponents: a content order
        std::sort(v.begin(), v.end(),
                  [&](const poly_term& a, const poly_term& b) { return key_of(a) < key_of(b); });
    }

    std::vector<std::pair<std::uint64_t, long>> key_of(const poly_term& t) const {
        std::vector<std::pair<std::uint64_t, long>> k;
        for (const auto& [b, x] : t.m)
            k.emplace_back(digest(b), x);
        std::sort(k.begin(), k.end());
        return k;
    }

    // m *= node^k, looking inside products so that x * (y/x) cancels.
    void merge(monomial& m, int node, long k) const {
        for (const auto& [b, x] : monomial_of(node)) {
            long& e = m[b];
            e += k * x;
            if (e == 0) m.erase(b);
        }
    }

    monomial monomial_of(int node) const {
        const auto it = m_monomial.find(node);
        if (it != m_monomial.end()) return it->second;
        return {{node, 1}};
    }

    // coefficient * prod factor^exponent as (coefficient, node).
    linear from_monomial(const numeric& c, const monomial& m) {
        // State factors times parameters over parameters, x y I3/I2: the parameters' quotient is
        // one node, x y (I3/I2), computed apart from the state (off the chain of operations on
        // the state, and shared by the products that have it) with the same operations.
        // (A reciprocal alone, x/I2, stays as it is: (1/I2) x would be one operation more.)
        bool parameter_above = false, parameter_below = false, state = false, state_below = false;
        for (const auto& [b, x] : m) {
            if (m_parametric[static_cast<std::size_t>(b)])
                (x > 0 ? parameter_above : parameter_below) = true;
            else
                state = true, state_below = state_below || x < 0;
        }
        if (parameter_above && parameter_below && state && !state_below) {
            monomial parameters;
            std::vector<int> num, pnum, pden;
            for (const auto& [b, x] : m) {
                if (!m_parametric[static_cast<std::size_t>(b)])
                    num.push_back(power(b, x));
                else if (x > 0)
                    pnum.push_back(power(b, x)), parameters.emplace(b, x);
                else
                    pden.push_back(power(b, -x)), parameters.emplace(b, x);
            }
            const int quotient = product(std::move(pnum), std::move(pden));
            m_monomial.emplace(quotient, parameters);
            num.push_back(quotient);
            const int id = product(std::move(num), {});
            m_monomial.emplace(id, m);
            return {c, id};
        }
        std::vector<int> num, den;
        for (const auto& [b, x] : m) {
            if (x > 0) num.push_back(power(b, x));
            if (x < 0) den.push_back(power(b, -x));
        }
        if (num.empty() && den.empty()) return {c, -1};
        if (num.size() == 1 && den.empty()) return {c, num[0]};
        int id;
        if (den.empty()) {
            id = product(std::move(num), {});
        } else if (num.empty()) {
            id = product({}, std::move(den));
        } else {
            // a/(b c) = a * (1/(b c)): the reciprocal is one node, shared by every product with
            // the same denominator (one division); used once, it prints back as a/(b*c).
            num.push_back(product({}, std::move(den)));
            id = product(std::move(num), {});
        }
        m_monomial.emplace(id, m);
        return {c, id};
    }

    // A product or a power: numeric coefficient times a product node.
    linear convert_product(const ex& e) {
        numeric coef = 1;
        monomial expo;
        const auto factor = [&](const ex& f) {
            if (is_a<numeric>(f)) {
                coef *= ex_to<numeric>(f);
                return;
            }
            if (is_a<GiNaC::power>(f) && is_a<numeric>(f.op(1))) {
                const numeric n = ex_to<numeric>(f.op(1));
                if (n.is_integer()) {
                    const linear b = convert(f.op(0));
                    const long k = n.to_long();
                    coef *= b.c.power(n);
                    if (b.node >= 0) merge(expo, b.node, k);
                    return;
                }
                if (n.is_rational() && n.denom().is_equal(2)) {
                    // x^(m/2), m odd: x^((m-1)/2) * sqrt(x), or its reciprocal.
                    const int b = materialize(convert(f.op(0)));
                    const int root = call("sqrt", {b});
                    const long m = n.numer().to_long();
                    if (m > 0) {
                        merge(expo, b, (m - 1) / 2);
                        merge(expo, root, 1);
                    } else {
                        merge(expo, b, -(-m - 1) / 2);
                        merge(expo, root, -1);
                    }
                    return;
                }
            }
            if (is_a<GiNaC::power>(f)) {
                const int b = materialize(convert(f.op(0)));
                const int x = materialize(convert(f.op(1)));
                merge(expo, call("pow", {b, x}), 1);
                return;
            }
            const linear v = convert(f);
            coef *= v.c;
            if (v.node >= 0) merge(expo, v.node, 1);
        };
        if (is_a<GiNaC::mul>(e))
            for (std::size_t i = 0; i < e.nops(); ++i)
                factor(e.op(i));
        else
            factor(e);
        if (coef.is_zero()) return {0, -1};
        if (const auto d = distribute(coef, expo)) return *d;
        return from_monomial(coef, expo);
    }

    // m S, S a sum every term of which cancels a factor with m: the sum of the products, which
    // saves the divisions and multiplications that cancel. I3 phi_dot sin(theta) (1/I3 +
    // cos(theta)^2/(I1 sin(theta)^2)) -> phi_dot sin(theta) + I3 cos(theta)^2 phi_dot/(I1
    // sin(theta)): one division fewer, and no reciprocal of I3. (The same terms, each scaled:
    // no new cancellation.)
    std::optional<linear> distribute(const numeric& coef, const monomial& m) {
        int sum_factor = -1;
        for (const auto& [b, x] : m) {
            if (x != 1 || m_p.nodes[static_cast<std::size_t>(b)].k != lowered_node::kind::sum)
                continue;
            if (sum_factor >= 0) return std::nullopt; // one sum at most
            sum_factor = b;
        }
        if (sum_factor < 0) return std::nullopt;
        const lowered_node s = m_p.nodes[static_cast<std::size_t>(sum_factor)];
        if (!s.value.is_zero()) return std::nullopt;
        monomial rest = m;
        rest.erase(sum_factor);
        std::vector<poly_term> terms;
        for (const auto& [c, id] : s.terms) {
            const monomial t = monomial_of(id);
            bool cancels = false;
            for (const auto& [b, x] : t) {
                const auto r = rest.find(b);
                if (r != rest.end() && (r->second > 0) != (x > 0)) cancels = true;
            }
            if (!cancels) return std::nullopt;
            poly_term p{coef * c, rest};
            for (const auto& [b, x] : t) {
                long& e = p.m[b];
                e += x;
                if (e == 0) p.m.erase(b);
            }
            terms.push_back(std::move(p));
        }
        numeric k = 0;
        combine_parameters(terms, k);
        sort_poly(terms);
        return horner(std::move(terms), k);
    }

    // x^k, k >= 1, by binary powering: shares x^2 between x^2, x^3, x^4, ...
    int power(int x, long k) {
        if (k == 1) return x;
        const int half = power(x, k / 2);
        const int square = product({half, half}, {});
        const int r = k % 2 ? product({square, x}, {}) : square;
        m_monomial.emplace(r, monomial{{x, k}});
        return r;
    }

  public:
    // The node `old` of another program (built from the same inputs) with its children already
    // mapped into this one (`mapped`, indexed by the other program's node ids): the same
    // structure, numbers folded. A sum's terms that became numbers join its constant; a product's
    // number factors join its coefficient; a sum keeps its leading term positive and takes a
    // common numeric factor outside where that saves multiplications (as plain_sum does); no
    // factoring or combining is redone, so the sharing of the other program stays. Throws
    // std::domain_error on a division by a number zero.
    linear fold(const lowered_node& old, const std::vector<linear>& mapped) {
        const auto at = [&](int id) { return mapped.at(static_cast<std::size_t>(id)); };
        switch (old.k) {
        case lowered_node::kind::input:
        case lowered_node::kind::number:
        case lowered_node::kind::constant:
            throw std::logic_error("lower: fold of a leaf");
        case lowered_node::kind::sum: {
            std::map<int, numeric> acc;
            numeric k = old.value;
            for (const auto& [c, id] : old.terms) {
                const linear v = at(id);
                if (v.node < 0)
                    k += c * v.c;
                else
                    acc[v.node] += c * v.c;
            }
            std::vector<poly_term> terms;
            for (const auto& [node, c] : acc)
                if (!c.is_zero()) terms.push_back({c, monomial{{node, 1}}});
            sort_poly(terms);
            return plain_sum(terms, k);
        }
        case lowered_node::kind::product: {
            numeric coef = 1;
            std::vector<int> num, den;
            for (int id : old.numerator) {
                const linear v = at(id);
                coef *= v.c;
                if (v.node >= 0) num.push_back(v.node);
            }
            for (int id : old.denominator) {
                const linear v = at(id);
                if (v.c.is_zero()) throw std::domain_error("lower: division by zero");
                coef /= v.c;
                if (v.node >= 0) den.push_back(v.node);
            }
            if (coef.is_zero()) return {0, -1};
            if (num.empty() && den.empty()) return {coef, -1};
            if (num.size() == 1 && den.empty()) return {coef, num[0]};
            return {coef, product(std::move(num), std::move(den))};
        }
        case lowered_node::kind::call: {
            std::vector<int> args;
            for (int id : old.args)
                args.push_back(materialize(at(id)));
            return {1, call(old.name, args)};
        }
        }
        throw std::logic_error("lower: unknown node kind");
    }

    int input_node(const ex& symbol) const { return m_input_of.at(symbol); }

    // Common sub-products: a pair of factors that two or more products (reachable from
    // `outputs`) multiply becomes one product node, shared: x y z and x y w -> (x y) z and (x y) w,
    // k products with the pair: k - 1 multiplications fewer. Greedy, the most frequent pair first
    // (ties: the smaller digests), until no pair is in two products. (Hash-consing shares equal
    // products only; a product is flattened into one list of factors, so a part of it that other
    // products have too, such as phi_dot sin(theta) in every omega, is found here.) A product's
    // numerator changes in place (its digest stays that of its first content: the program is
    // still the same for the same expressions) and the node list is left with parents possibly
    // before children: renumber() afterwards.
    void share_products(const std::vector<int>& outputs) {
        for (;;) {
            std::vector<char> reached(m_p.nodes.size(), 0);
            std::vector<int> stack(outputs.begin(), outputs.end()), products;
            while (!stack.empty()) {
                const int id = stack.back();
                stack.pop_back();
                if (reached[static_cast<std::size_t>(id)]) continue;
                reached[static_cast<std::size_t>(id)] = 1;
                const lowered_node& n = m_p.nodes[static_cast<std::size_t>(id)];
                if (n.k == lowered_node::kind::product && n.numerator.size() >= 2)
                    products.push_back(id);
                for (int c : children(n))
                    stack.push_back(c);
            }
            // pair (by digest order) -> products that have it
            std::map<std::pair<int, int>, std::vector<int>> have;
            for (int id : products) {
                const std::vector<int>& f = m_p.nodes[static_cast<std::size_t>(id)].numerator;
                std::set<std::pair<int, int>> pairs;
                for (std::size_t i = 0; i < f.size(); ++i)
                    for (std::size_t j = i + 1; j < f.size(); ++j)
                        pairs.insert(before(f[j], f[i]) ? std::make_pair(f[j], f[i])
                                                        : std::make_pair(f[i], f[j]));
                for (const auto& pr : pairs)
                    have[pr].push_back(id);
            }
            const std::pair<int, int>* best = nullptr;
            std::size_t best_count = 1;
            for (const auto& [pr, ids] : have) {
                if (ids.size() < best_count) continue;
                const bool wins =
                    ids.size() > best_count ||
                    (best && std::make_pair(digest(pr.first), digest(pr.second)) <
                                 std::make_pair(digest(best->first), digest(best->second)));
                if (wins) best = &pr, best_count = ids.size();
            }
            if (!best) return;
            const auto [a, b] = *best;
            const std::vector<int> ids = have[*best];
            const int pair = product({a, b}, {});
            for (int id : ids) {
                if (id == pair) continue;
                std::vector<int> f = m_p.nodes[static_cast<std::size_t>(id)].numerator;
                f.erase(std::find(f.begin(), f.end(), a));
                f.erase(std::find(f.begin(), f.end(), b));
                f.push_back(pair);
                sort_nodes(f);
                lowered_node& n = m_p.nodes[static_cast<std::size_t>(id)];
                m_table.erase(product_key(n.numerator, n.denominator));
                n.numerator = std::move(f);
                m_table.emplace(product_key(n.numerator, n.denominator), id);
            }
        }
    }

    int constant_pi() {
        lowered_node n;
        n.k = lowered_node::kind::constant;
        n.name = "pi";
        return intern(std::move(n), "K|pi");
    }

    int number(const numeric& v) {
        lowered_node n;
        n.k = lowered_node::kind::number;
        n.value = v;
        return intern(std::move(n), "N|" + numeric_text(v));
    }

    int sum(std::vector<std::pair<numeric, int>> terms, const numeric& k) {
        sort_terms(terms);
        lowered_node n;
        n.k = lowered_node::kind::sum;
        n.value = k;
        std::string key = "S|" + numeric_text(k);
        for (const auto& [c, id] : terms)
            key += "|" + numeric_text(c) + ":" + std::to_string(id);
        n.terms = std::move(terms);
        return intern(std::move(n), key);
    }

    static std::string product_key(const std::vector<int>& num, const std::vector<int>& den) {
        std::string key = "P";
        for (int id : num)
            key += "|" + std::to_string(id);
        key += "|/";
        for (int id : den)
            key += "|" + std::to_string(id);
        return key;
    }

    int product(std::vector<int> num, std::vector<int> den) {
        sort_nodes(num);
        sort_nodes(den);
        const std::string key = product_key(num, den);
        lowered_node n;
        n.k = lowered_node::kind::product;
        n.numerator = std::move(num);
        n.denominator = std::move(den);
        return intern(std::move(n), key);
    }

    int call(const std::string& name, const std::vector<int>& args) {
        std::string key = "C|" + name;
        for (int id : args)
            key += "|" + std::to_string(id);
        lowered_node n;
        n.k = lowered_node::kind::call;
        n.name = name;
        n.args = args;
        return intern(std::move(n), key);
    }

  private:
    std::uint64_t digest(int id) const { return m_p.nodes[static_cast<std::size_t>(id)].digest; }

    bool before(int a, int b) const {
        const std::uint64_t da = digest(a), db = digest(b);
        if (da == db && a != b)
            throw std::logic_error("lower: digest collision between two different subexpressions");
        return da < db;
    }

    void sort_nodes(std::vector<int>& v) const {
        std::sort(v.begin(), v.end(), [&](int a, int b) { return before(a, b); });
    }

    void sort_terms(std::vector<std::pair<numeric, int>>& v) const {
        std::sort(v.begin(), v.end(),
                  [&](const auto& a, const auto& b) { return before(a.second, b.second); });
    }

    int intern(lowered_node n, const std::string& key) {
        const auto it = m_table.find(key);
        if (it != m_table.end()) return it->second;
        std::uint64_t h = fnv_offset;
        const auto child = [&](int id) {
            const lowered_node& c = m_p.nodes[static_cast<std::size_t>(id)];
            mix(h, c.digest);
            n.height = std::max(n.height, c.height + 1);
        };
        switch (n.k) {
        case lowered_node::kind::input:
            mix(h, "input"), mix(h, n.name);
            break;
        case lowered_node::kind::number:
            mix(h, "number"), mix(h, numeric_text(n.value));
            break;
        case lowered_node::kind::constant:
            mix(h, "constant"), mix(h, n.name);
            break;
        case lowered_node::kind::sum:
            mix(h, "sum"), mix(h, numeric_text(n.value));
            for (const auto& [c, id] : n.terms)
                mix(h, numeric_text(c)), child(id);
            break;
        case lowered_node::kind::product:
            mix(h, "product");
            for (int id : n.numerator)
                child(id);
            mix(h, "/");
            for (int id : n.denominator)
                child(id);
            break;
        case lowered_node::kind::call:
            mix(h, "call"), mix(h, n.name);
            for (int id : n.args)
                child(id);
            break;
        }
        n.digest = h;
        bool parametric = n.k != lowered_node::kind::input; // inputs: set by the constructor
        for (int c : children(n))
            parametric = parametric && m_parametric[static_cast<std::size_t>(c)];
        const int id = static_cast<int>(m_p.nodes.size());
        m_p.nodes.push_back(std::move(n));
        m_parametric.push_back(parametric);
        m_table.emplace(key, id);
        return id;
    }

    lowered_program& m_p;
    std::map<std::string, int> m_table;
    std::map<ex, linear, GiNaC::ex_is_less> m_memo;
    std::map<ex, int, GiNaC::ex_is_less> m_input_of;
    std::map<int, monomial> m_monomial; // product nodes as monomials, for factoring sums
    std::vector<char> m_parametric;     // node -> depends on parameters and numbers only
    std::map<int, ex> m_ex_of;          // parameter-only node (or input) -> its expression
};

bool is_hoisted_trig(const lowered_program& p, const lowered_node& n) {
    if (n.k != lowered_node::kind::call || (n.name != "sin" && n.name != "cos") ||
        n.args.size() != 1)
        return false;
    const lowered_node& a = p.nodes[static_cast<std::size_t>(n.args[0])];
    return a.k == lowered_node::kind::input && is_identifier(a.name);
}

// ---- printing ----

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
        throw std::logic_error("lower: unknown node kind");
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

} // namespace

op_count count_ops(const ex& e) {
    return naive_counter()(e);
}

namespace {

// Temporaries, their names and the printed operation count of a program whose DAG and outputs
// are built.
void schedule(lowered_program& p, const lower_options& options) {
    // Which nodes are of parameters and numbers alone (children before parents).
    p.parametric.assign(p.nodes.size(), 0);
    for (std::size_t i = 0; i < p.nodes.size(); ++i) {
        const lowered_node& n = p.nodes[i];
        bool parametric = n.k != lowered_node::kind::input;
        if (n.k == lowered_node::kind::input)
            for (const program_input& in : p.inputs)
                if (in.name == n.name) parametric = in.parameter;
        for (int c : children(n))
            parametric = parametric && p.parametric[static_cast<std::size_t>(c)];
        p.parametric[i] = parametric;
    }

    // Uses of each node reachable from the outputs (each occurrence in a parent counts).
    std::vector<int> uses(p.nodes.size(), 0);
    std::vector<char> reached(p.nodes.size(), 0);
    std::vector<int> order; // depth-first post-order, children in digest order
    std::function<void(int)> visit = [&](int id) {
        if (reached[static_cast<std::size_t>(id)]) return;
        reached[static_cast<std::size_t>(id)] = 1;
        for (int c : children(p.nodes[static_cast<std::size_t>(id)])) {
            ++uses[static_cast<std::size_t>(c)];
            visit(c);
        }
        order.push_back(id);
    };
    for (int o : p.outputs) {
        ++uses[static_cast<std::size_t>(o)];
        visit(o);
    }

    // Temporaries: sums, products and calls used more than once; sin/cos of inputs always; and a
    // subexpression whose inline text would exceed max_inline_ops operations (short statements:
    // readable, and shallow expression templates for array scalar types such as Eigen's).
    std::vector<int> hoisted, temps;
    std::vector<std::size_t> inline_ops(p.nodes.size(), 0);
    for (int id : order) { // children before parents
        const auto u = static_cast<std::size_t>(id);
        const lowered_node& n = p.nodes[u];
        const bool compound = n.k == lowered_node::kind::sum ||
                              n.k == lowered_node::kind::product || n.k == lowered_node::kind::call;
        std::size_t cost = 0;
        if (n.k == lowered_node::kind::sum) cost = n.terms.size() + (n.value.is_zero() ? 0 : 1);
        if (n.k == lowered_node::kind::product) cost = n.numerator.size() + n.denominator.size();
        if (n.k == lowered_node::kind::call) cost = 1;
        for (int c : children(n))
            cost += inline_ops[static_cast<std::size_t>(c)];
        if (is_hoisted_trig(p, n)) {
            hoisted.push_back(id);
        } else if (compound && (uses[u] >= 2 || cost > options.max_inline_ops)) {
            temps.push_back(id);
        } else {
            inline_ops[u] = cost;
        }
    }
    // sin/cos first, in input order (sin before cos).
    std::vector<int> trig;
    for (const program_input& in : p.inputs)
        for (const char* f : {"sin", "cos"})
            for (int id : hoisted) {
                const lowered_node& n = p.nodes[static_cast<std::size_t>(id)];
                if (n.name == f && p.nodes[static_cast<std::size_t>(n.args[0])].name == in.name)
                    trig.push_back(id);
            }
    std::vector<int> all = trig;
    all.insert(all.end(), temps.begin(), temps.end());
    int counter = 0;
    for (int id : all) {
        const lowered_node& n = p.nodes[static_cast<std::size_t>(id)];
        std::string name;
        if (is_hoisted_trig(p, n)) {
            name = n.name + "_" + p.nodes[static_cast<std::size_t>(n.args[0])].name;
        } else {
            char buf[32];
            std::snprintf(buf, sizeof buf, "t%03d", counter++);
            name = buf;
        }
        p.steps.push_back({id, name});
        p.temporary_name[id] = name;
    }

    const program_printer printer(p, "S");
    for (const auto& s : p.steps)
        p.after += printer.definition(s.node).ops;
    for (int o : p.outputs)
        p.after += printer.ref(o).ops;
}

// Orders the nodes children before parents again (after share_products), by a depth-first
// post-order from each node in turn, and renames the children and outputs to match.
void renumber(lowered_program& p) {
    const std::size_t count = p.nodes.size();
    std::vector<int> new_id(count, -1), order;
    std::vector<char> on_stack(count, 0);
    std::function<void(int)> visit = [&](int id) {
        const auto u = static_cast<std::size_t>(id);
        if (new_id[u] >= 0) return;
        if (on_stack[u]) throw std::logic_error("lower: a cycle in the program");
        on_stack[u] = 1;
        for (int c : children(p.nodes[u]))
            visit(c);
        new_id[u] = static_cast<int>(order.size());
        order.push_back(id);
    };
    for (std::size_t i = 0; i < count; ++i)
        visit(static_cast<int>(i));
    std::vector<lowered_node> nodes;
    nodes.reserve(count);
    const auto rename = [&](std::vector<int>& v) {
        for (int& id : v)
            id = new_id[static_cast<std::size_t>(id)];
    };
    for (int id : order) {
        lowered_node n = std::move(p.nodes[static_cast<std::size_t>(id)]);
        for (auto& t : n.terms)
            t.second = new_id[static_cast<std::size_t>(t.second)];
        rename(n.numerator);
        rename(n.denominator);
        rename(n.args);
        nodes.push_back(std::move(n));
    }
    p.nodes = std::move(nodes);
    rename(p.outputs);
}

op_count naive_ops(const std::vector<ex>& outputs) {
    naive_counter naive;
    op_count r;
    for (const ex& e : outputs)
        r += naive(e);
    return r;
}

} // namespace

lowered_program lower(const std::vector<ex>& outputs, const std::vector<program_input>& inputs,
                      const lower_options& options) {
    lowered_program p;
    p.inputs = inputs;
    p.before = naive_ops(outputs);
    {
        dag_builder b(p);
        for (const ex& e : outputs)
            p.outputs.push_back(b.materialize(b.convert(e)));
        b.share_products(p.outputs);
    }
    renumber(p);
    schedule(p, options);
    return p;
}

std::optional<lowered_program> lower_folded(const std::vector<ex>& outputs,
                                            const std::vector<program_input>& inputs,
                                            const GiNaC::exmap& values,
                                            const lower_options& options) {
    // The runtime program: inputs in `values` are still inputs here.
    lowered_program runtime;
    runtime.inputs = inputs;
    {
        dag_builder b(runtime);
        for (const ex& e : outputs)
            runtime.outputs.push_back(b.materialize(b.convert(e)));
    }
    lowered_program p;
    for (const program_input& in : inputs)
        if (!values.count(in.symbol)) p.inputs.push_back(in);
    dag_builder b(p);
    std::vector<linear> mapped(runtime.nodes.size(), linear{0, -1});
    try {
        for (std::size_t i = 0; i < runtime.nodes.size(); ++i) {
            const lowered_node& n = runtime.nodes[i];
            switch (n.k) {
            case lowered_node::kind::input: {
                const program_input* in = nullptr;
                for (const program_input& x : inputs)
                    if (x.name == n.name) in = &x;
                if (!in) throw std::logic_error("lower: unknown input '" + n.name + "'");
                const auto v = values.find(in->symbol);
                if (v == values.end()) {
                    mapped[i] = {1, b.input_node(in->symbol)};
                } else {
                    if (!is_a<numeric>(v->second) || !ex_to<numeric>(v->second).is_real())
                        throw std::logic_error("lower: folded input '" + n.name +
                                               "' is not a real number");
                    mapped[i] = {ex_to<numeric>(v->second), -1};
                }
                break;
            }
            case lowered_node::kind::number:
                mapped[i] = {n.value, -1};
                break;
            case lowered_node::kind::constant:
                mapped[i] = {1, b.constant_pi()};
                break;
            default:
                mapped[i] = b.fold(n, mapped);
            }
        }
    } catch (const std::domain_error&) {
        return std::nullopt; // a folded value makes a denominator zero
    }
    for (int o : runtime.outputs)
        p.outputs.push_back(b.materialize(mapped[static_cast<std::size_t>(o)]));
    b.share_products(p.outputs);
    // The substituted expressions, printed naively: what the header reports as "before".
    std::vector<ex> substituted;
    for (const ex& e : outputs)
        substituted.push_back(e.subs(values));
    p.before = naive_ops(substituted);
    renumber(p);
    schedule(p, options);
    return p;
}

std::string print_node(const lowered_program& program, int node, const std::string& scalar) {
    return program_printer(program, scalar).ref(node).text;
}

std::string print_definition(const lowered_program& program, int node, const std::string& scalar) {
    return program_printer(program, scalar).definition(node).text;
}

std::vector<bool> used_inputs(const lowered_program& program) {
    std::vector<char> reached(program.nodes.size(), 0);
    std::vector<int> stack(program.outputs.begin(), program.outputs.end());
    while (!stack.empty()) {
        const int id = stack.back();
        stack.pop_back();
        if (reached[static_cast<std::size_t>(id)]) continue;
        reached[static_cast<std::size_t>(id)] = 1;
        for (int c : children(program.nodes[static_cast<std::size_t>(id)]))
            stack.push_back(c);
    }
    std::vector<bool> used(program.inputs.size(), false);
    for (std::size_t i = 0; i < program.nodes.size(); ++i) {
        const lowered_node& n = program.nodes[i];
        if (!reached[i] || n.k != lowered_node::kind::input) continue;
        for (std::size_t k = 0; k < program.inputs.size(); ++k)
            if (program.inputs[k].name == n.name) used[k] = true;
    }
    return used;
}

bool is_zero_node(const lowered_program& program, int node) {
    const lowered_node& n = program.nodes.at(static_cast<std::size_t>(node));
    return n.k == lowered_node::kind::number && n.value.is_zero();
}

std::vector<numeric> evaluate(const lowered_program& program, const GiNaC::exmap& values) {
    std::vector<ex> v(program.nodes.size());
    std::map<std::string, ex> input_value; // a missing value leaves the symbol: not a number
    for (const program_input& in : program.inputs) {
        const auto it = values.find(in.symbol);
        input_value[in.name] = it != values.end() ? it->second : in.symbol;
    }
    for (std::size_t i = 0; i < program.nodes.size(); ++i) {
        const lowered_node& n = program.nodes[i];
        const auto at = [&](int id) { return v[static_cast<std::size_t>(id)]; };
        const ex input = n.k == lowered_node::kind::input ? input_value.at(n.name) : ex();
        const ex r = node_expression(n, input, at);
        v[i] = GiNaC::evalf(r);
    }
    std::vector<numeric> out;
    for (int o : program.outputs) {
        const ex r = v[static_cast<std::size_t>(o)];
        if (!is_a<numeric>(r))
            throw std::logic_error("lower: an output did not evaluate to a number");
        out.push_back(ex_to<numeric>(r));
    }
    return out;
}

} // namespace rotgen
