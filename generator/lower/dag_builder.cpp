// rotgen — lowering: interning (content digests, the node table) and conversion of GiNaC
// expressions into DAG nodes. The rules are in lower.hpp.
#include "lower/detail.hpp"

#include <algorithm>
#include <set>
#include <sstream>
#include <stdexcept>

namespace rotgen::lowering {

using GiNaC::ex_to;
using GiNaC::is_a;

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

const std::set<std::string>& known_calls() {
    static const std::set<std::string> f{"sin",  "cos",  "tan",  "asin", "acos", "atan", "atan2",
                                         "sinh", "cosh", "tanh", "exp",  "log",  "abs"};
    return f;
}

} // namespace

std::string numeric_text(const numeric& n) {
    std::ostringstream os;
    os << n;
    return os.str();
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

} // namespace rotgen::lowering

namespace rotgen {
std::vector<int> node_children(const lowered_node& node) {
    return lowering::children(node);
}
} // namespace rotgen

namespace rotgen::lowering {

dag_builder::dag_builder(lowered_program& program, bool hoist) : m_p(program), m_hoist(hoist) {
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

int dag_builder::materialize(const linear& v) {
    if (v.node < 0) return number(v.c);
    if (v.c.is_equal(1)) return v.node;
    return sum({{v.c, v.node}}, 0);
}

linear dag_builder::convert(const ex& e) {
    const auto it = m_memo.find(e);
    if (it != m_memo.end()) return it->second;
    const linear r = convert_uncached(e);
    m_memo.emplace(e, r);
    return r;
}

linear dag_builder::convert_uncached(const ex& e) {
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
linear dag_builder::convert_sum(const ex& e, bool combine) {
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

// A numerator or denominator from normal(): a sum is converted as it is (it is in normal
// form already; combining it again would call normal() on it again, for ever).
linear dag_builder::convert_normal(const ex& e) {
    if (!is_a<GiNaC::add>(e)) return convert(e);
    const auto it = m_memo.find(e);
    if (it != m_memo.end()) return it->second;
    const linear r = convert_sum(e, false);
    m_memo.emplace(e, r);
    return r;
}

// The GiNaC expression a parameter-only node stands for (inputs are in m_ex_of from the
// start).
ex dag_builder::expression(int id) {
    const auto it = m_ex_of.find(id);
    if (it != m_ex_of.end()) return it->second;
    const lowered_node n = m_p.nodes[static_cast<std::size_t>(id)];
    if (n.k == lowered_node::kind::input)
        throw std::logic_error("lower: input '" + n.name + "' without a symbol");
    const ex r = node_expression(n, ex(), [&](int child) { return expression(child); });
    m_ex_of.emplace(id, r);
    return r;
}

int dag_builder::constant_pi() {
    lowered_node n;
    n.k = lowered_node::kind::constant;
    n.name = "pi";
    return intern(std::move(n), "K|pi");
}

int dag_builder::number(const numeric& v) {
    lowered_node n;
    n.k = lowered_node::kind::number;
    n.value = v;
    return intern(std::move(n), "N|" + numeric_text(v));
}

int dag_builder::sum(std::vector<std::pair<numeric, int>> terms, const numeric& k) {
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

std::string dag_builder::product_key(const std::vector<int>& num, const std::vector<int>& den) {
    std::string key = "P";
    for (int id : num)
        key += "|" + std::to_string(id);
    key += "|/";
    for (int id : den)
        key += "|" + std::to_string(id);
    return key;
}

int dag_builder::product(std::vector<int> num, std::vector<int> den) {
    sort_nodes(num);
    sort_nodes(den);
    const std::string key = product_key(num, den);
    lowered_node n;
    n.k = lowered_node::kind::product;
    n.numerator = std::move(num);
    n.denominator = std::move(den);
    return intern(std::move(n), key);
}

int dag_builder::call(const std::string& name, const std::vector<int>& args) {
    std::string key = "C|" + name;
    for (int id : args)
        key += "|" + std::to_string(id);
    lowered_node n;
    n.k = lowered_node::kind::call;
    n.name = name;
    n.args = args;
    return intern(std::move(n), key);
}

bool dag_builder::before(int a, int b) const {
    const std::uint64_t da = digest(a), db = digest(b);
    if (da == db && a != b)
        throw std::logic_error("lower: digest collision between two different subexpressions");
    return da < db;
}

void dag_builder::sort_nodes(std::vector<int>& v) const {
    std::sort(v.begin(), v.end(), [&](int a, int b) { return before(a, b); });
}

void dag_builder::sort_terms(std::vector<std::pair<numeric, int>>& v) const {
    std::sort(v.begin(), v.end(),
              [&](const auto& a, const auto& b) { return before(a.second, b.second); });
}

int dag_builder::intern(lowered_node n, const std::string& key) {
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

} // namespace rotgen::lowering
