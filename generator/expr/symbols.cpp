#include "expr/symbols.hpp"

#include <algorithm>
#include <regex>

namespace rotgen {

namespace {
coordinate_symbols make_symbols() {
    using GiNaC::realsymbol;
    coordinate_symbols s{
        {realsymbol("phi", "\\varphi"), realsymbol("theta", "\\theta"), realsymbol("psi", "\\psi")},
        {realsymbol("phi_dot", "\\dot{\\varphi}"), realsymbol("theta_dot", "\\dot{\\theta}"),
         realsymbol("psi_dot", "\\dot{\\psi}")},
        {realsymbol("phi_ddot", "\\ddot{\\varphi}"), realsymbol("theta_ddot", "\\ddot{\\theta}"),
         realsymbol("psi_ddot", "\\ddot{\\psi}")},
        {realsymbol("p_phi", "p_{\\varphi}"), realsymbol("p_theta", "p_{\\theta}"),
         realsymbol("p_psi", "p_{\\psi}")},
        {realsymbol("omega1", "\\omega_{1}"), realsymbol("omega2", "\\omega_{2}"),
         realsymbol("omega3", "\\omega_{3}")},
        realsymbol("t", "t")};
    return s;
}
} // namespace

const coordinate_symbols& symbols() {
    static const coordinate_symbols s = make_symbols();
    return s;
}

const std::array<std::string, 3>& coordinate_names() {
    static const std::array<std::string, 3> names{"phi", "theta", "psi"};
    return names;
}

const std::vector<std::string>& known_functions() {
    static const std::vector<std::string> f{"sin",  "cos",   "tan",  "asin", "acos",
                                            "atan", "atan2", "sinh", "cosh", "tanh",
                                            "exp",  "log",   "sqrt", "abs",  "pow"};
    return f;
}

std::string reserved_reason(const std::string& name) {
    static const std::vector<std::string> state{
        "phi",      "theta",      "psi",      "phi_dot", "theta_dot", "psi_dot",
        "phi_ddot", "theta_ddot", "psi_ddot", "p_phi",   "p_theta",   "p_psi",
        "omega1",   "omega2",     "omega3",   "t",       "energy"};
    if (std::find(state.begin(), state.end(), name) != state.end())
        return "it names a coordinate, rate, momentum or output";
    static const std::vector<std::string> ginac{"I",       "Pi",   "pi",   "Euler",
                                                "Catalan", "beta", "zeta", "e"};
    if (std::find(ginac.begin(), ginac.end(), name) != ginac.end())
        return "it is a built-in constant or special function";
    const auto& f = known_functions();
    if (std::find(f.begin(), f.end(), name) != f.end()) return "it is a function name";
    // Names used inside generated code: the template scalar, arguments, temporaries, hoisted trig.
    static const std::vector<std::string> generated{"T", "y",      "dydt",       "J",
                                                    "p", "params", "state_size", "std"};
    if (std::find(generated.begin(), generated.end(), name) != generated.end())
        return "it is used by the generated code";
    static const std::regex temporary("t[0-9]+|(sin|cos)_(phi|theta|psi)|rg_.*");
    if (std::regex_match(name, temporary)) return "it is used by the generated code";
    static const std::vector<std::string> keywords{
        "auto",      "bool",      "break",    "case",     "char",      "class",    "const",
        "constexpr", "continue",  "default",  "delete",   "do",        "double",   "else",
        "enum",      "extern",    "false",    "float",    "for",       "friend",   "goto",
        "if",        "inline",    "int",      "long",     "namespace", "new",      "operator",
        "private",   "protected", "public",   "register", "return",    "short",    "signed",
        "sizeof",    "static",    "struct",   "switch",   "template",  "this",     "throw",
        "true",      "try",       "typedef",  "typename", "union",     "unsigned", "using",
        "virtual",   "void",      "volatile", "while"};
    if (std::find(keywords.begin(), keywords.end(), name) != keywords.end())
        return "it is a C++ keyword";
    return {};
}

} // namespace rotgen
