// rotgen — lowering: folding. A runtime program's nodes rebuilt with some inputs replaced by
// exact numbers, its structure (sharing, factoring) kept: lower_folded().
#include "lower/detail.hpp"

#include <stdexcept>

namespace rotgen::lowering {

// The node `old` of another program (built from the same inputs) with its children already
// mapped into this one (`mapped`, indexed by the other program's node ids): the same
// structure, numbers folded. A sum's terms that became numbers join its constant; a product's
// number factors join its coefficient; a sum keeps its leading term positive and takes a
// common numeric factor outside where that saves multiplications (as plain_sum does); no
// factoring or combining is redone, so the sharing of the other program stays. Throws
// std::domain_error on a division by a number zero.
linear dag_builder::fold(const lowered_node& old, const std::vector<linear>& mapped) {
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

} // namespace rotgen::lowering

namespace rotgen {

using GiNaC::ex_to;
using GiNaC::is_a;
using namespace lowering;

std::optional<lowered_program> lower_folded(const std::vector<ex>& outputs,
                                            const std::vector<program_input>& inputs,
                                            const GiNaC::exmap& values,
                                            const lower_options& options) {
    // The runtime program: inputs in `values` are still inputs here.
    lowered_program runtime;
    runtime.inputs = inputs;
    {
        dag_builder b(runtime, options.hoist_parameters);
        for (const ex& e : outputs)
            runtime.outputs.push_back(b.materialize(b.convert(e)));
    }
    lowered_program p;
    for (const program_input& in : inputs)
        if (!values.count(in.symbol)) p.inputs.push_back(in);
    dag_builder b(p, options.hoist_parameters);
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

} // namespace rotgen
