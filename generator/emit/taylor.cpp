// rotgen — emission: the Taylor printer (taylor.hpp). The lowered DAG becomes a list of series
// operations, one per node that varies along the solution, printed once for order 0 (the values)
// and once inside the loop over the orders (the recurrences, calls to the helpers of
// templates/taylor_helpers.hpp.in).
#include "emit/taylor.hpp"

#include "emit/printer.hpp"
#include "support/error.hpp"

#include <cctype>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rotgen {

using GiNaC::numeric;

namespace {

struct series_op {
    enum kind_t { sum, scaled, mul, square, div, sin_cos, exp, log, sqrt, pow, atan2 } kind;
    explicit series_op(kind_t k) : kind(k) {}
    int out = -1, out2 = -1; // the series written (out2: the cosine of a sine-cosine pair)
    int a = -1, b = -1;      // operand series; -1: none (a division of a constant)
    int r = -1;              // atan2: the series x^2 + y^2
    std::string scale;       // a constant factor (empty: none); pow: the exponent
    std::vector<std::pair<numeric, int>> terms; // sum: coefficient, series
    std::string constant;                       // sum: the constant part (empty: none)
};

std::string numbered(const char* prefix, std::size_t i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%s%03zu", prefix, i);
    return buf;
}

class taylor_builder {
  public:
    explicit taylor_builder(const lowered_program& p) : m_p(p), m_named(p) {
        m_named.steps.clear();
        m_named.temporary_name.clear();
        classify_inputs();
    }

    taylor_body build();

  private:
    const lowered_node& node(int id) const { return m_p.nodes.at(static_cast<std::size_t>(id)); }
    bool constant(int id) const { return m_const.at(static_cast<std::size_t>(id)); }

    void classify_inputs();
    std::string constant_text(int id);
    std::string named_constant(const std::string& text);
    int new_series(const std::string& name);
    int add(series_op op, const std::string& name = "");
    // A node as c times a series: a sum of one varying term and no constant is its term scaled
    // (the scale joins the user's coefficient or constant factor: no series of its own).
    std::pair<numeric, int> linear_of(int id);
    int series_of(int id);
    int sum_series(const lowered_node& n);
    int product_series(const lowered_node& n);
    int chain(const std::vector<int>& factors);
    int call_series(const lowered_node& n);
    std::string order_zero(const series_op& op) const;
    // fixed: k is a compile-time constant (taylor_fixed); the sums of products are folded
    std::string order_k(const series_op& op, bool fixed) const;
    struct rate_lines {
        std::vector<std::string> loop, fixed; // one per state, in taylor() and taylor_fixed()
        std::set<int> folded; // the operations taylor_fixed computes inside a rate (not apart)
    };
    rate_lines rates();
    std::string folded_rate(int series, const numeric& c, int uses, std::set<int>& folded) const;
    int uses(int series) const;
    std::vector<std::string> head(const std::string& m) const;
    std::vector<std::string> orders(const std::vector<std::string>& rates, bool fixed,
                                    const std::set<int>& folded = {}) const;
    std::string sum_text(const series_op& op, const std::string& index, bool with_constant) const;
    std::string ref(int s, const std::string& index) const {
        return m_names.at(s) + "[" + index + "]";
    }

    const lowered_program& m_p;
    lowered_program m_named; // the program with the constants named k000, ... (for printing)
    std::vector<char> m_const;
    std::map<int, int> m_state_of; // input node -> state index
    int m_time_node = -1, m_time = -1;
    std::size_t m_n = 0;
    std::vector<std::string> m_names;          // series -> name
    std::map<int, int> m_series;               // node -> series
    std::map<int, std::pair<int, int>> m_trig; // argument series -> (sin, cos) series
    std::vector<series_op> m_ops;
    std::vector<std::string> m_constants; // `const T k000 = ...;` lines
    std::set<std::string> m_calls;
};

void taylor_builder::classify_inputs() {
    m_const.assign(m_p.nodes.size(), 1);
    for (std::size_t id = 0; id < m_p.nodes.size(); ++id) {
        const lowered_node& n = m_p.nodes[id];
        if (n.k == lowered_node::kind::input) {
            for (const auto& in : m_p.inputs) {
                if (in.name != n.name) continue;
                if (in.definition.rfind("y[", 0) == 0) {
                    const int i = std::stoi(in.definition.substr(2));
                    m_state_of[static_cast<int>(id)] = i;
                    m_const[id] = 0;
                } else if (in.name == "t") {
                    m_time_node = static_cast<int>(id);
                    m_const[id] = 0;
                }
            }
            continue;
        }
        for (int c : node_children(n))
            if (!m_const[static_cast<std::size_t>(c)]) m_const[id] = 0;
    }
    m_n = m_state_of.size();
    m_names.resize(m_n);
    for (const auto& [id, i] : m_state_of) {
        if (i < 0 || static_cast<std::size_t>(i) >= m_n)
            throw std::logic_error("taylor: state index out of range");
        m_names[static_cast<std::size_t>(i)] = node(id).name;
        m_series[id] = i;
    }
}

std::string taylor_builder::named_constant(const std::string& text) {
    const std::string name = numbered("k", m_constants.size());
    // numbers alone (S(1)/S(3)) convert to T explicitly (T may be an array type)
    bool numbers_only = true;
    for (char ch : text)
        if (std::isalpha(static_cast<unsigned char>(ch)) && ch != 'S') numbers_only = false;
    m_constants.push_back("    const T " + name + " = " +
                          (numbers_only ? "T(" + text + ")" : text) + ";");
    return name;
}

// A constant as printed where it is used: an input by name, a number as a literal, anything
// else a named constant (computed once, before the orders).
std::string taylor_builder::constant_text(int id) {
    const lowered_node& n = node(id);
    if (n.k == lowered_node::kind::input) return n.name;
    if (n.k == lowered_node::kind::number) return print_number(n.value);
    const auto named = m_named.temporary_name.find(id);
    if (named != m_named.temporary_name.end()) return named->second;
    for (int c : node_children(n))
        constant_text(c); // children first, so that the definition refers to their names
    const std::string name = named_constant(print_definition(m_named, id));
    m_named.temporary_name[id] = name;
    return name;
}

int taylor_builder::new_series(const std::string& name) {
    m_names.push_back(name.empty() ? numbered("u", m_names.size() - m_n) : name);
    return static_cast<int>(m_names.size() - 1);
}

int taylor_builder::add(series_op op, const std::string& name) {
    op.out = new_series(name);
    m_ops.push_back(op);
    return op.out;
}

std::pair<numeric, int> taylor_builder::linear_of(int id) {
    const lowered_node& n = node(id);
    if (n.k == lowered_node::kind::sum && n.value.is_zero() && n.terms.size() == 1 &&
        !constant(n.terms[0].second) && !m_series.count(id)) {
        const auto inner = linear_of(n.terms[0].second);
        return {n.terms[0].first * inner.first, inner.second};
    }
    return {1, series_of(id)};
}

int taylor_builder::series_of(int id) {
    const auto it = m_series.find(id);
    if (it != m_series.end()) return it->second;
    const lowered_node& n = node(id);
    int s = -1;
    if (id == m_time_node) {
        m_time = s = new_series("time");
    } else if (n.k == lowered_node::kind::sum) {
        s = sum_series(n);
    } else if (n.k == lowered_node::kind::product) {
        s = product_series(n);
    } else if (n.k == lowered_node::kind::call) {
        s = call_series(n);
    } else {
        throw std::logic_error("taylor: node of unexpected kind varies with the state");
    }
    m_series[id] = s;
    return s;
}

// c0 + sum c_i b_i: the constant terms join c0 (one named constant), the others are series.
int taylor_builder::sum_series(const lowered_node& n) {
    series_op op{series_op::sum};
    std::string k0 = n.value.is_zero() ? "" : print_number(n.value);
    for (const auto& [c, child] : n.terms) {
        if (!constant(child)) {
            const auto l = linear_of(child);
            op.terms.emplace_back(c * l.first, l.second);
            continue;
        }
        const std::string v = constant_text(child);
        const std::string magnitude = abs(c).is_equal(1) ? v : print_number(abs(c)) + "*" + v;
        if (k0.empty())
            k0 = c.is_negative() ? "-" + magnitude : magnitude;
        else
            k0 += (c.is_negative() ? " - " : " + ") + magnitude;
    }
    if (!k0.empty()) op.constant = named_constant(k0);
    if (op.constant.empty() && op.terms.size() == 1 && op.terms[0].first.is_equal(1))
        return op.terms[0].second;
    return add(op);
}

// A chain of binary products (x x is a square).
int taylor_builder::chain(const std::vector<int>& factors) {
    int left = factors.at(0);
    for (std::size_t j = 1; j < factors.size(); ++j) {
        series_op op{left == factors[j] ? series_op::square : series_op::mul};
        op.a = left;
        op.b = factors[j];
        left = add(op);
    }
    return left;
}

// K prod a_i / prod b_j, K the constant factors (one named constant), a_i, b_j series.
int taylor_builder::product_series(const lowered_node& n) {
    std::vector<int> num, den;
    std::vector<std::string> knum, kden;
    numeric coefficient = 1; // of factors that are scaled series
    for (int f : n.numerator) {
        if (constant(f)) {
            knum.push_back(constant_text(f));
            continue;
        }
        const auto l = linear_of(f);
        coefficient *= l.first;
        num.push_back(l.second);
    }
    for (int f : n.denominator) {
        if (constant(f)) {
            kden.push_back(constant_text(f));
            continue;
        }
        const auto l = linear_of(f);
        coefficient /= l.first;
        den.push_back(l.second);
    }
    if (!coefficient.is_equal(1)) knum.insert(knum.begin(), print_number(coefficient));
    const auto product = [](const std::vector<std::string>& v) {
        std::string s;
        for (const auto& f : v)
            s += (s.empty() ? "" : "*") + f;
        return s;
    };
    std::string scale;
    if (!kden.empty())
        scale = named_constant((knum.empty() ? "S(1)" : "(" + product(knum) + ")") + "/(" +
                               product(kden) + ")");
    else if (knum.size() == 1 && knum[0].find_first_of("()/*+- ") == std::string::npos)
        scale = knum[0];
    else if (!knum.empty())
        scale = named_constant(product(knum));
    series_op op{series_op::div};
    op.scale = scale;
    if (!den.empty()) {
        op.a = num.empty() ? -1 : chain(num);
        op.b = chain(den);
        return add(op);
    }
    if (num.size() == 1) {
        if (scale.empty()) return num[0];
        op.kind = series_op::scaled;
        op.a = num[0];
        return add(op);
    }
    const std::vector<int> head(num.begin(), num.end() - 1);
    op.a = chain(head);
    op.b = num.back();
    op.kind = op.a == op.b ? series_op::square : series_op::mul;
    return add(op);
}

int taylor_builder::call_series(const lowered_node& n) {
    const std::string& f = n.name;
    const auto unsupported = [&](const std::string& why) {
        return taylor_unsupported("the Taylor recurrences do not cover " + why + " (in the rates)");
    };
    for (int a : n.args)
        if (constant(a) && f != "pow")
            throw unsupported("'" + f + "' of a constant beside a varying argument");
    if (f == "sin" || f == "cos") {
        const int a = series_of(n.args.at(0));
        auto it = m_trig.find(a);
        if (it == m_trig.end()) {
            series_op op{series_op::sin_cos};
            op.a = a;
            const int s = add(op, "sin_" + m_names[static_cast<std::size_t>(a)]);
            m_ops.back().out2 = new_series("cos_" + m_names[static_cast<std::size_t>(a)]);
            it = m_trig.emplace(a, std::make_pair(s, m_ops.back().out2)).first;
            m_calls.insert("sin");
            m_calls.insert("cos");
        }
        return f == "sin" ? it->second.first : it->second.second;
    }
    series_op op{series_op::sum};
    if (f == "exp" || f == "log" || f == "sqrt") {
        op.kind = f == "exp" ? series_op::exp : f == "log" ? series_op::log : series_op::sqrt;
    } else if (f == "pow") {
        if (!constant(n.args.at(1))) throw unsupported("a power with a varying exponent");
        op.kind = series_op::pow;
        op.scale = constant_text(n.args.at(1));
    } else if (f == "atan2") {
        op.kind = series_op::atan2;
        const int y = series_of(n.args.at(0)), x = series_of(n.args.at(1));
        series_op r{series_op::sum};
        r.terms = {{1, chain({x, x})}, {1, chain({y, y})}};
        op.r = add(r);
        op.a = y;
        op.b = x;
        m_calls.insert(f);
        return add(op);
    } else {
        throw unsupported("'" + f + "'");
    }
    op.a = series_of(n.args.at(0));
    m_calls.insert(f);
    return add(op);
}

std::string taylor_builder::sum_text(const series_op& op, const std::string& index,
                                     bool with_constant) const {
    std::string s = with_constant ? op.constant : "";
    for (const auto& [c, id] : op.terms) {
        const std::string v = ref(id, index);
        const std::string term = abs(c).is_equal(1) ? v : print_number(abs(c)) + "*" + v;
        if (s.empty())
            s = c.is_negative() ? "-" + term : term;
        else
            s += (c.is_negative() ? " - " : " + ") + term;
    }
    return s.empty() ? "T(S(0))" : s;
}

std::string taylor_builder::order_zero(const series_op& op) const {
    const std::string out = ref(op.out, "0") + " = ";
    const std::string k = op.scale.empty() ? "" : op.scale + "*";
    const auto a = [&] { return ref(op.a, "0"); };
    switch (op.kind) {
    case series_op::sum:
        return out + sum_text(op, "0", true) + ";";
    case series_op::scaled:
        return out + k + a() + ";";
    case series_op::mul:
        return out + k + a() + "*" + ref(op.b, "0") + ";";
    case series_op::square:
        return out + k + a() + "*" + a() + ";";
    case series_op::div:
        return out + (op.a < 0 ? (op.scale.empty() ? "S(1)" : op.scale) : k + a()) + "/" +
               ref(op.b, "0") + ";";
    case series_op::sin_cos:
        return out + "sin(" + a() + "); " + ref(op.out2, "0") + " = cos(" + a() + ");";
    case series_op::exp:
    case series_op::log:
    case series_op::sqrt: {
        static const char* const f[] = {"exp", "log", "sqrt"};
        return out + f[op.kind - series_op::exp] + "(" + a() + ");";
    }
    case series_op::pow:
        return out + "pow(" + a() + ", " + op.scale + ");";
    case series_op::atan2:
        return out + "atan2(" + a() + ", " + ref(op.b, "0") + ");";
    }
    throw std::logic_error("taylor: unknown operation");
}

std::string taylor_builder::order_k(const series_op& op, bool fixed) const {
    const std::string out = ref(op.out, "k") + " = ";
    // generic: taylor_mul(a, b, k); fixed: taylor_mul<k>(a, b)
    const auto call = [&](const char* f, const std::string& args) {
        return std::string("detail::") + f + (fixed ? "<k>(" + args + ")" : "(" + args + ", k)");
    };
    const std::string k = op.scale.empty() ? "" : op.scale + "*";
    const std::string a = op.a < 0 ? "" : m_names[static_cast<std::size_t>(op.a)];
    const std::string b = op.b < 0 ? "" : m_names[static_cast<std::size_t>(op.b)];
    const std::string u = m_names[static_cast<std::size_t>(op.out)];
    switch (op.kind) {
    case series_op::sum:
        return out + sum_text(op, "k", false) + ";";
    case series_op::scaled:
        return out + k + ref(op.a, "k") + ";";
    case series_op::mul:
        return out + k + call("taylor_mul", a + ", " + b) + ";";
    case series_op::square:
        return out + k + call("taylor_square", a) + ";";
    case series_op::div:
        return out +
               call("taylor_div",
                    (op.a < 0 ? "T(S(0))" : k + ref(op.a, "k")) + ", " + b + ", " + u) +
               ";";
    case series_op::sin_cos:
        return call("taylor_sin_cos",
                    u + ", " + m_names[static_cast<std::size_t>(op.out2)] + ", " + a) +
               ";";
    case series_op::exp:
        return out + "detail::taylor_exp(" + u + ", " + a + ", k);";
    case series_op::log:
        return out + "detail::taylor_log(" + u + ", " + a + ", k);";
    case series_op::sqrt:
        return out + "detail::taylor_sqrt(" + u + ", " + a + ", k);";
    case series_op::pow:
        return out + "detail::taylor_pow(" + u + ", " + a + ", " + op.scale + ", k);";
    case series_op::atan2:
        return out + "detail::taylor_atan2(" + u + ", " + a + ", " + b + ", " +
               m_names[static_cast<std::size_t>(op.r)] + ", k);";
    }
    throw std::logic_error("taylor: unknown operation");
}

// The operands of the operations that read series s.
int taylor_builder::uses(int s) const {
    int n = 0;
    for (const auto& op : m_ops) {
        n += (op.a == s) + (op.b == s) + (op.r == s);
        for (const auto& t : op.terms)
            n += t.second == s;
    }
    return n;
}

// taylor_fixed's rate y^[k] = c f^[k-1] / k where f is a product (or a square) of two series that
// nothing else reads: the product at order k - 1 scaled by s = c scale / k inside the sum
// (detail::taylor_mul with a factor), which takes two operations off the chain from one order's
// coefficients to the next (the free top's expansion at order 11 took 6% less time; used where
// the recurrences are few, taylor_body::few_operations). Empty when
// the rate is not of that kind (`uses`: the reads of the series, the rates' included).
std::string taylor_builder::folded_rate(int series, const numeric& c, int uses,
                                        std::set<int>& folded) const {
    std::size_t i = 0;
    while (i < m_ops.size() && m_ops[i].out != series)
        ++i;
    if (i == m_ops.size() || uses != 1) return "";
    const series_op& op = m_ops[i];
    if (op.kind != series_op::mul && op.kind != series_op::square) return "";
    std::string s; // c scale / k, a T
    if (op.scale.empty())
        s = "T(" + (c.is_equal(1) ? "" : c.is_equal(-1) ? "-" : print_number(c) + "*") + "inv_k)";
    else
        s = c.is_equal(1)    ? op.scale + "*inv_k"
            : c.is_equal(-1) ? "-" + op.scale + "*inv_k"
                             : op.scale + "*(" + print_number(c) + "*inv_k)";
    folded.insert(static_cast<int>(i));
    const std::string a = m_names[static_cast<std::size_t>(op.a)];
    if (op.kind == series_op::square) return "detail::taylor_square<k - 1>(" + a + ", " + s + ");";
    return "detail::taylor_mul<k - 1>(" + a + ", " + m_names[static_cast<std::size_t>(op.b)] +
           ", " + s + ");";
}

// The state's coefficient k, one line per state: y^[k] = f^[k-1] / k.
taylor_builder::rate_lines taylor_builder::rates() {
    std::vector<std::pair<numeric, int>> linear(m_p.outputs.size(), {0, -1});
    for (std::size_t i = 0; i < m_p.outputs.size(); ++i) // first: each may add series
        if (!constant(m_p.outputs[i])) linear[i] = linear_of(m_p.outputs[i]);
    rate_lines lines;
    for (std::size_t i = 0; i < m_p.outputs.size(); ++i) {
        const std::string x = m_names.at(i) + "[k] = ";
        const auto [c, series] = linear[i];
        if (series < 0) {
            lines.loop.push_back(x + "k == 1 ? T(" + constant_text(m_p.outputs[i]) +
                                 ") : T(S(0));");
            lines.fixed.push_back(lines.loop.back());
            continue;
        }
        const std::string f = m_names[static_cast<std::size_t>(series)] + "[k - 1]*inv_k;";
        lines.loop.push_back(x + (c.is_equal(1)    ? f
                                  : c.is_equal(-1) ? "-" + f
                                                   : print_number(c) + "*" + f));
        int reads = uses(series);
        for (const auto& l : linear)
            reads += l.second == series;
        const std::string folded = folded_rate(series, c, reads, lines.folded);
        lines.fixed.push_back(folded.empty() ? lines.loop.back() : x + folded);
    }
    return lines;
}

// Up to the orders' loop: the series' pointers (m coefficients each), the constants, order 0.
std::vector<std::string> taylor_builder::head(const std::string& m) const {
    std::vector<std::string> lines;
    for (const char* f : {"atan2", "cos", "exp", "log", "pow", "sin", "sqrt"})
        if (m_calls.count(f)) lines.push_back(std::string("    using std::") + f + ";");
    lines.push_back("    using S = typename detail::scalar_of<T>::type;");
    std::string all;
    for (const auto& c : m_constants)
        all += c;
    for (const auto& op : m_ops)
        all += order_zero(op);
    if (m_time < 0) lines.push_back("    (void)t;");
    if (all.find("p.") == std::string::npos) lines.push_back("    (void)p;");
    lines.push_back("    " + m + "; // coefficients per series");
    for (std::size_t s = 0; s < m_names.size(); ++s)
        lines.push_back("    T* const " + m_names[s] + " = c + " + std::to_string(s) + " * m;");
    lines.insert(lines.end(), m_constants.begin(), m_constants.end());
    lines.push_back("    // order 0: the values");
    if (m_time >= 0) lines.push_back("    time[0] = t;");
    for (const auto& op : m_ops)
        lines.push_back("    " + order_zero(op));
    return lines;
}

// Orders 1 .. order: a loop (generic), or one copy per order with k a constant (fixed).
std::vector<std::string> taylor_builder::orders(const std::vector<std::string>& rates, bool fixed,
                                                const std::set<int>& folded) const {
    std::vector<std::string> lines;
    lines.push_back("    // orders 1 .. " + std::string(fixed ? "Order" : "order") +
                    ": the state's from the rates' (y^[k] = f^[k-1] / k), then each operation's");
    if (fixed) {
        lines.push_back(
            "    detail::taylor_orders<Order>([&](auto order_k) ROTGEN_TAYLOR_LAMBDA {");
        lines.push_back("        constexpr int k = decltype(order_k)::value;");
    } else {
        lines.push_back("    for (int k = 1; k <= order; ++k) {");
    }
    lines.push_back("        const S inv_k = S(1)/S(k);");
    for (const auto& r : rates)
        lines.push_back("        " + r);
    const bool more = m_ops.size() > folded.size() || m_time >= 0;
    const std::string in = fixed && more ? "    " : "";
    if (more)
        lines.push_back(fixed ? "        if constexpr (k < Order) {"
                              : "        if (k == order) break;");
    if (m_time >= 0) lines.push_back(in + "        time[k] = k == 1 ? T(S(1)) : T(S(0));");
    for (std::size_t i = 0; i < m_ops.size(); ++i)
        if (!folded.count(static_cast<int>(i)))
            lines.push_back(in + "        " + order_k(m_ops[i], fixed));
    if (fixed && more) lines.push_back("        }");
    lines.push_back(fixed ? "    });" : "    }");
    return lines;
}

taylor_body taylor_builder::build() {
    const rate_lines r = rates();       // first: it may name constants
    const bool few = m_ops.size() <= 8; // taylor_body::few_operations
    const auto join = [](std::vector<std::string> a, const std::vector<std::string>& b) {
        a.insert(a.end(), b.begin(), b.end());
        std::string text;
        for (std::size_t i = 0; i < a.size(); ++i)
            text += (i ? "\n" : "") + a[i];
        return text;
    };
    taylor_body b;
    b.text = join(head("const int m = order + 1;"), orders(r.loop, false));
    b.fixed_text = join(head("constexpr int m = Order + 1;"),
                        few ? orders(r.fixed, true, r.folded) : orders(r.loop, true));
    b.series = m_names.size();
    b.operations = m_ops.size();
    b.few_operations = few;
    return b;
}

} // namespace

taylor_body print_taylor_body(const lowered_program& rhs) {
    return taylor_builder(rhs).build();
}

} // namespace rotgen
