// rotgen — emission: prepared<T> (prepared.hpp).
#include "emit/prepared.hpp"

#include "emit/emit.hpp"
#include "emit/printer.hpp"

#include <cctype>
#include <set>
#include <string>
#include <vector>

namespace rotgen {

namespace {

// The functions a definition calls (`sqrt(`), for its using-declarations.
std::set<std::string> calls_in(const std::string& text) {
    static const std::vector<std::string> math{"abs", "acos", "asin", "atan", "atan2",
                                               "cos", "cosh", "exp",  "log",  "pow",
                                               "sin", "sinh", "sqrt", "tan",  "tanh"};
    std::set<std::string> r;
    for (const auto& f : math) {
        const std::string call = f + "(";
        for (std::size_t at = text.find(call); at != std::string::npos;
             at = text.find(call, at + 1))
            if (at == 0 || !(std::isalnum(static_cast<unsigned char>(text[at - 1])) ||
                             text[at - 1] == '_' || text[at - 1] == '.'))
                r.insert(f);
    }
    return r;
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
        members += "\n    T " + member + "{};";
        definitions += "\n    p." + member + " = " + text + ";";
        for (const auto& f : calls_in(text))
            calls.insert(f);
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
