// rotgen — lowering: products. Monomials (factor -> exponent), integer powers by binary
// powering, parameter quotients, reciprocals, distribution over a cancelling sum, and sub-products
// shared between products. The rules are in lower.hpp.
#include "lower/detail.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace rotgen::lowering {

using GiNaC::ex_to;
using GiNaC::is_a;

// m *= node^k, looking inside products so that x * (y/x) cancels.
void dag_builder::merge(monomial& m, int node, long k) const {
    for (const auto& [b, x] : monomial_of(node)) {
        long& e = m[b];
        e += k * x;
        if (e == 0) m.erase(b);
    }
}

monomial dag_builder::monomial_of(int node) const {
    const auto it = m_monomial.find(node);
    if (it != m_monomial.end()) return it->second;
    return {{node, 1}};
}

// Hoisting: x y I3/I1 -> x y (I3/I1) and x/(I1 y) -> x (1/I1)/y, the parameters' factor a node
// of its own (a constant, computed once per parameter set: a division by a parameter becomes a
// multiplication). One parameter factor above the bar alone, x I3, stays as it is.
std::optional<linear> dag_builder::hoisted_parameters(const numeric& c, const monomial& m) {
    long count = 0;
    bool below = false, state = false;
    for (const auto& [b, x] : m) {
        if (!m_parametric[static_cast<std::size_t>(b)]) {
            state = true;
            continue;
        }
        count += x > 0 ? x : -x;
        below = below || x < 0;
    }
    if (!m_hoist || !state || (count < 2 && !below)) return std::nullopt;
    monomial parameters;
    std::vector<int> pnum, pden, num, den;
    for (const auto& [b, x] : m) {
        if (!m_parametric[static_cast<std::size_t>(b)])
            (x > 0 ? num : den).push_back(power(b, x > 0 ? x : -x));
        else
            (x > 0 ? pnum : pden).push_back(power(b, x > 0 ? x : -x)), parameters.emplace(b, x);
    }
    const int factor =
        pnum.size() == 1 && pden.empty() ? pnum[0] : product(std::move(pnum), std::move(pden));
    m_monomial.emplace(factor, parameters);
    num.push_back(factor);
    if (!den.empty()) num.push_back(product({}, std::move(den)));
    const int id = product(std::move(num), {});
    m_monomial.emplace(id, m);
    return linear{c, id};
}

// coefficient * prod factor^exponent as (coefficient, node).
linear dag_builder::from_monomial(const numeric& c, const monomial& m) {
    if (const auto hoisted = hoisted_parameters(c, m)) return *hoisted;
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
linear dag_builder::convert_product(const ex& e) {
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
std::optional<linear> dag_builder::distribute(const numeric& coef, const monomial& m) {
    int sum_factor = -1;
    for (const auto& [b, x] : m) {
        if (x != 1 || m_p.nodes[static_cast<std::size_t>(b)].k != lowered_node::kind::sum) continue;
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
int dag_builder::power(int x, long k) {
    if (k == 1) return x;
    const int half = power(x, k / 2);
    const int square = product({half, half}, {});
    const int r = k % 2 ? product({square, x}, {}) : square;
    m_monomial.emplace(r, monomial{{x, k}});
    return r;
}

// Common sub-products: a pair of factors that two or more products (reachable from
// `outputs`) multiply becomes one product node, shared: x y z and x y w -> (x y) z and (x y) w,
// k products with the pair: k - 1 multiplications fewer. Greedy, the most frequent pair first
// (ties: the smaller digests), until no pair is in two products. (Hash-consing shares equal
// products only; a product is flattened into one list of factors, so a part of it that other
// products have too, such as phi_dot sin(theta) in every omega, is found here.) A product's
// numerator changes in place (its digest stays that of its first content: the program is
// still the same for the same expressions) and the node list is left with parents possibly
// before children: renumber() afterwards.
void dag_builder::share_products(const std::vector<int>& outputs) {
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

} // namespace rotgen::lowering
