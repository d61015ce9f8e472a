// rotgen — emission: prepared<T> (prepared.hpp).
#include "emit/prepared.hpp"

#include "emit/emit.hpp"
#include "emit/printer.hpp"

#include <set>
#include <string>
#include <vector>

namespace rotgen {

namespace {

// The functions a constant's definition calls (for its using-declarations): the calls in its
// node's subtree, down to the named nodes it reads.
void calls_below(const lowered_program& p, int id, bool root, std::set<std::string>& calls) {
    if (!root && p.temporary_name.count(id)) return;
    const lowered_node& n = p.nodes.at(static_cast<std::size_t>(id));
    if (n.k == lowered_node::kind::call) calls.insert(n.name);
    for (int c : node_children(n))
        calls_below(p, c, false, calls);
}

} // namespace

std::string prepared_text(const lowered_form& lf) {
    std::string members, definitions;
    std::set<std::string> calls;
    bool literals = false;
    op_count ops;
    for (const auto& c : lf.constants) {
        const lowered_program& prog = lf.functions.at(c.function).program;
        const std::string text = print_definition(prog, c.node);
        ops += definition_op_count(prog, c.node);
        const std::string member = c.name.substr(2); // p.c000 -> c000
        members +=
            "\n    T " + member + "{}; ///< a subexpression of the parameters, set by prepare()";
        definitions += "\n    p." + member + " = " + text + ";";
        calls_below(prog, c.node, true, calls);
        literals = literals || text.find("S(") != std::string::npos;
    }
    std::string body;
    for (const auto& f : calls)
        body += "    using std::" + f + ";\n";
    if (literals) body += "    using S = typename detail::scalar_of<T>::type;\n";
    body += "    prepared<T> p;\n    static_cast<params<T>&>(p) = parameters;" + definitions +
            "\n    return p;";
    return fill_template("prepared.hpp.in", {{"count", std::to_string(lf.constants.size())},
                                             {"ops", std::to_string(ops.total())},
                                             {"members", members},
                                             {"body", body}});
}

} // namespace rotgen
