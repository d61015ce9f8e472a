// rotgen — lowering, internal: the hash-consed DAG builder and what the parts of lower/ share.
// Not part of lower/'s interface (lower.hpp is): included by lower/*.cpp only.
//
// dag_builder turns GiNaC expressions into nodes of a lowered_program (lower.hpp explains the
// rules). Its definitions are spread by concern:
//   dag_builder.cpp      interning (digests, the node table) and conversion of GiNaC expressions;
//   factor_sums.cpp      sums: parameter combination, Horner factoring, flattening, plain sums;
//   factor_products.cpp  products: monomials, powers, distribution, shared sub-products;
//   fold.cpp             folding numbers into another program's structure (lower_folded).
#pragma once

#include "lower/lower.hpp"

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rotgen::lowering {

using GiNaC::ex;
using GiNaC::numeric;

// Exact text of a number (GiNaC's own printing of a rational: "3/7", "-2").
std::string numeric_text(const numeric& n);

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

// A call as lowering names it (sqrt and pow included), applied to GiNaC arguments.
ex apply_call(const std::string& name, const std::vector<ex>& a);

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

// The children of a node: sum terms, numerator, denominator, call arguments.
std::vector<int> children(const lowered_node& n);

// Operations of `outputs` printed naively, each on its own (lowered_program::before).
op_count naive_ops(const std::vector<ex>& outputs);

// Operations of the program as emit/printer.hpp prints it, temporaries plus outputs
// (lowered_program::after): the printer's choices (inline products flattened, numbers multiplied
// into inline sums, negations absorbed), counted without printing. The emitter checks that the
// two agree.
op_count printed_ops(const lowered_program& p);

// Temporaries, their names and the printed operation count of a program whose DAG and outputs
// are built.
void schedule(lowered_program& p, const lower_options& options);

// Orders the nodes children before parents again (after share_products), by a depth-first
// post-order from each node in turn, and renames the children and outputs to match.
void renumber(lowered_program& p);

// Builds the hash-consed DAG.
class dag_builder {
  public:
    // hoist: lower_options::hoist_parameters (parameters of a product as one factor)
    explicit dag_builder(lowered_program& program, bool hoist = false);

    int materialize(const linear& v);

    linear convert(const ex& e);

    linear convert_uncached(const ex& e);

    // `combine`: false for the numerator or denominator of a fraction normal() has just made.
    linear convert_sum(const ex& e, bool combine = true);

    // Terms with the same state-dependent factors become one term, the sum of their parameter
    // coefficients brought to a single fraction by normal(): x y/I1 - x y/I2 -> x y (I2 - I1)/(I1
    // I2). A difference of rounded reciprocals has no accurate digits left when I1 ~ I2; I2 - I1
    // of two inputs is exact. The constant k joins the terms with no state-dependent factor.
    // (Horner's factoring below never makes such a sum again: it divides terms by common
    // factors, which keeps their state-dependent parts distinct.)
    void combine_parameters(std::vector<poly_term>& terms, numeric& k);

    // c = n/d, expanded, with common factors cancelled by normal(). n and d are unique up to a
    // constant factor, fixed here (d has integer coefficients with no common divisor), and up to
    // the sign, which the DAG fixes (every sum has its leading term positive): the same program
    // every run, though normal()'s own output changes from run to run. Memoised for the process:
    // the same few coefficients recur in every sum, output and candidate of a model, and normal()
    // is the dearest step of lowering.
    static std::pair<ex, ex> single_fraction(const ex& c);

    // A numerator or denominator from normal(): a sum is converted as it is (it is in normal
    // form already; combining it again would call normal() on it again, for ever).
    linear convert_normal(const ex& e);

    monomial state_part(const monomial& m) const;

    ex parameter_part(const monomial& m);

    // The GiNaC expression a parameter-only node stands for (inputs are in m_ex_of from the
    // start).
    ex expression(int id);

    // Greedy multivariate Horner scheme: pull the factor shared by the most terms out of them,
    // recursively (x y + x z + w -> x (y + z) + w). Denominator factors count as factors too
    // (a/s + b/s -> (a + b)/s). Ties go to the smaller digest, so the result is deterministic.
    linear horner(std::vector<poly_term> terms, numeric k);

    // A linear combination of sums that have like terms whose coefficients involve parameters,
    // or the same term with coefficients that cancel, as one sum: (x + a y) - (x + b y) -> (a - b)
    // y, with the coefficients combined as in combine_parameters (not the difference of two nearly
    // equal products when a ~ b) and x cancelled exactly. (The factoring above leaves such
    // combinations where the expression multiplied sums out: c A - c B -> c (A - B).) Other sums
    // stay nodes, computed once for all their uses: flattening sums whose like terms have numeric
    // coefficients only (specialised kernels) costs more operations than it saves (+20% on the
    // full tensor's).
    void flatten_overlapping_sums(std::vector<poly_term>& terms, numeric& k);

    // A sum with no factor to pull out: leading term positive, a common numeric factor outside
    // when that saves multiplications.
    linear plain_sum(const std::vector<poly_term>& poly, const numeric& k);

    static bool all_rational(const std::vector<std::pair<numeric, int>>& terms, const numeric& k);

    void sort_poly(std::vector<poly_term>& v) const;

    std::vector<std::pair<std::uint64_t, long>> key_of(const poly_term& t) const;

    // m *= node^k, looking inside products so that x * (y/x) cancels.
    void merge(monomial& m, int node, long k) const;

    monomial monomial_of(int node) const;

    // coefficient * prod factor^exponent as (coefficient, node).
    linear from_monomial(const numeric& c, const monomial& m);

    // A product or a power: numeric coefficient times a product node.
    linear convert_product(const ex& e);

    // m S, S a sum every term of which cancels a factor with m: the sum of the products, which
    // saves the divisions and multiplications that cancel. I3 phi_dot sin(theta) (1/I3 +
    // cos(theta)^2/(I1 sin(theta)^2)) -> phi_dot sin(theta) + I3 cos(theta)^2 phi_dot/(I1
    // sin(theta)): one division fewer, and no reciprocal of I3. (The same terms, each scaled:
    // no new cancellation.)
    std::optional<linear> distribute(const numeric& coef, const monomial& m);

    // x^k, k >= 1, by binary powering: shares x^2 between x^2, x^3, x^4, ...
    int power(int x, long k);

    // The node `old` of another program (built from the same inputs) with its children already
    // mapped into this one (`mapped`, indexed by the other program's node ids): the same
    // structure, numbers folded. A sum's terms that became numbers join its constant; a product's
    // number factors join its coefficient; a sum keeps its leading term positive and takes a
    // common numeric factor outside where that saves multiplications (as plain_sum does); no
    // factoring or combining is redone, so the sharing of the other program stays. Throws
    // std::domain_error on a division by a number zero.
    linear fold(const lowered_node& old, const std::vector<linear>& mapped);

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
    void share_products(const std::vector<int>& outputs);

    int constant_pi();

    int number(const numeric& v);

    int sum(std::vector<std::pair<numeric, int>> terms, const numeric& k);

    static std::string product_key(const std::vector<int>& num, const std::vector<int>& den);

    int product(std::vector<int> num, std::vector<int> den);

    int call(const std::string& name, const std::vector<int>& args);

    std::uint64_t digest(int id) const { return m_p.nodes[static_cast<std::size_t>(id)].digest; }

    bool before(int a, int b) const;

    void sort_nodes(std::vector<int>& v) const;

    void sort_terms(std::vector<std::pair<numeric, int>>& v) const;

    int intern(lowered_node n, const std::string& key);

  private:
    // The parameters of a monomial with state factors as one factor of their own, when hoisting
    // and there are two or more of them or one below the bar: nullopt otherwise.
    std::optional<linear> hoisted_parameters(const numeric& c, const monomial& m);

    lowered_program& m_p;
    bool m_hoist;
    std::map<std::string, int> m_table;
    std::map<ex, linear, GiNaC::ex_is_less> m_memo;
    std::map<ex, int, GiNaC::ex_is_less> m_input_of;
    std::map<int, monomial> m_monomial; // product nodes as monomials, for factoring sums
    std::vector<char> m_parametric;     // node -> depends on parameters and numbers only
    std::map<int, ex> m_ex_of;          // parameter-only node (or input) -> its expression
};

} // namespace rotgen::lowering
