// rotgen — lowering: the program's order and temporaries. lower() builds the DAG (detail.hpp),
// orders it children before parents, and chooses the temporaries: nodes used more than once,
// sin/cos of the inputs, and subexpressions too long to print inline.
#include "lower/detail.hpp"

#include <cstdio>
#include <functional>
#include <regex>
#include <stdexcept>

namespace rotgen {

using namespace lowering;

namespace {

bool is_identifier(const std::string& s) {
    static const std::regex id("[A-Za-z_][A-Za-z0-9_]*");
    return std::regex_match(s, id);
}

bool is_hoisted_trig(const lowered_program& p, const lowered_node& n) {
    if (n.k != lowered_node::kind::call || (n.name != "sin" && n.name != "cos") ||
        n.args.size() != 1)
        return false;
    const lowered_node& a = p.nodes[static_cast<std::size_t>(n.args[0])];
    return a.k == lowered_node::kind::input && is_identifier(a.name);
}

// Which nodes are of parameters and numbers alone (children before parents).
void mark_parametric(lowered_program& p) {
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
}

// Uses of each node reachable from the outputs (each occurrence in a parent counts), and those
// nodes in a depth-first post-order, children in digest order.
std::vector<int> count_uses(const lowered_program& p, std::vector<int>& uses) {
    uses.assign(p.nodes.size(), 0);
    std::vector<char> reached(p.nodes.size(), 0);
    std::vector<int> order;
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
    return order;
}

// The nodes a non-parametric node or an output uses directly (children of state-dependent
// parents): where hoisting, the parameter-only ones among them are read by name.
std::vector<char> used_by_state(const lowered_program& p, const std::vector<int>& order) {
    std::vector<char> r(p.nodes.size(), 0);
    for (int id : order)
        if (!p.parametric[static_cast<std::size_t>(id)])
            for (int c : children(p.nodes[static_cast<std::size_t>(id)]))
                r[static_cast<std::size_t>(c)] = 1;
    for (int o : p.outputs)
        r[static_cast<std::size_t>(o)] = 1;
    return r;
}

// Temporaries: sums, products and calls used more than once; sin/cos of inputs always
// (`hoisted`); and a subexpression whose inline text would exceed max_inline_ops operations
// (short statements: readable, and shallow expression templates for array scalar types such as
// Eigen's). With hoisting, a parameter-only one of these, or one a state-dependent node uses, is
// a constant instead. `order` has children before parents.
void choose_temporaries(const lowered_program& p, const std::vector<int>& order,
                        const std::vector<int>& uses, const lower_options& options,
                        std::vector<int>& hoisted, std::vector<int>& temps,
                        std::vector<int>& constants) {
    std::vector<std::size_t> inline_ops(p.nodes.size(), 0);
    const std::vector<char> by_state =
        options.hoist_parameters ? used_by_state(p, order) : std::vector<char>(p.nodes.size(), 0);
    for (int id : order) {
        const auto u = static_cast<std::size_t>(id);
        const lowered_node& n = p.nodes[u];
        const bool compound = n.k == lowered_node::kind::sum ||
                              n.k == lowered_node::kind::product || n.k == lowered_node::kind::call;
        const bool constant = options.hoist_parameters && compound && p.parametric[u];
        std::size_t cost = 0;
        if (n.k == lowered_node::kind::sum) cost = n.terms.size() + (n.value.is_zero() ? 0 : 1);
        if (n.k == lowered_node::kind::product) cost = n.numerator.size() + n.denominator.size();
        if (n.k == lowered_node::kind::call) cost = 1;
        for (int c : children(n))
            cost += inline_ops[static_cast<std::size_t>(c)];
        if (is_hoisted_trig(p, n)) {
            hoisted.push_back(id);
        } else if (constant && (by_state[u] || uses[u] >= 2 || cost > options.max_inline_ops)) {
            constants.push_back(id);
        } else if (compound && (uses[u] >= 2 || cost > options.max_inline_ops)) {
            temps.push_back(id);
        } else {
            inline_ops[u] = cost;
        }
    }
}

// The constants, named p.c000, p.c001, ... in order (lower_form names them again, once for all
// the functions of a form).
void name_constants(lowered_program& p, const std::vector<int>& constants) {
    for (std::size_t i = 0; i < constants.size(); ++i) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "p.c%03zu", i);
        p.constants.push_back({constants[i], buf});
        p.temporary_name[constants[i]] = buf;
    }
}

// The steps: sin/cos first, in input order (sin before cos), named sin_<input>, cos_<input>; then
// the other temporaries, t000, t001, ...
void name_temporaries(lowered_program& p, const std::vector<int>& hoisted,
                      const std::vector<int>& temps) {
    std::vector<int> all;
    for (const program_input& in : p.inputs)
        for (const char* f : {"sin", "cos"})
            for (int id : hoisted) {
                const lowered_node& n = p.nodes[static_cast<std::size_t>(id)];
                if (n.name == f && p.nodes[static_cast<std::size_t>(n.args[0])].name == in.name)
                    all.push_back(id);
            }
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
}

} // namespace

void lowering::schedule(lowered_program& p, const lower_options& options) {
    mark_parametric(p);
    std::vector<int> uses;
    const std::vector<int> order = count_uses(p, uses);
    std::vector<int> hoisted, temps, constants;
    choose_temporaries(p, order, uses, options, hoisted, temps, constants);
    name_constants(p, constants);
    name_temporaries(p, hoisted, temps);
    p.after = printed_ops(p);
}

// Orders the nodes children before parents again (after share_products), by a depth-first
// post-order from each node in turn, and renames the children and outputs to match.
void lowering::renumber(lowered_program& p) {
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

lowered_program lower(const std::vector<ex>& outputs, const std::vector<program_input>& inputs,
                      const lower_options& options) {
    lowered_program p;
    p.inputs = inputs;
    p.before = naive_ops(outputs);
    {
        dag_builder b(p, options.hoist_parameters);
        for (const ex& e : outputs)
            p.outputs.push_back(b.materialize(b.convert(e)));
        b.share_products(p.outputs);
    }
    renumber(p);
    schedule(p, options);
    return p;
}

} // namespace rotgen
