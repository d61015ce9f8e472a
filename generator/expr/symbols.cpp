#include "expr/symbols.hpp"

#include "expr/angles.hpp"

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

std::vector<std::string> momentum_names(const angle_convention& c) {
    const auto& n = c.names;
    return {"p_" + n[0], "p_" + n[1], "p_" + n[2]};
}

std::string display_name(const GiNaC::symbol& x, const angle_convention& c) {
    const auto& s = symbols();
    const auto& n = c.names;
    for (int i = 0; i < 3; ++i) {
        if (x.is_equal(s.q[i])) return n[i];
        if (x.is_equal(s.qd[i])) return n[i] + "_dot";
        if (x.is_equal(s.qdd[i])) return n[i] + "_ddot";
        if (x.is_equal(s.p[i])) return "p_" + n[i];
    }
    return x.get_name();
}

std::string display_tex_name(const GiNaC::symbol& x, const angle_convention& c) {
    if (c.is_default()) return x.get_TeX_name();
    const auto& s = symbols();
    const auto& n = c.names;
    static const std::vector<std::string> greek{"alpha", "beta", "gamma", "delta", "eta",
                                                "theta", "phi",  "psi",   "chi",   "xi"};
    for (int i = 0; i < 3; ++i) {
        const std::string base =
            n[i] == "phi" ? "\\varphi"
            : std::find(greek.begin(), greek.end(), n[i]) != greek.end()
                ? "\\" + n[i]
                : "\\mathrm{" + std::regex_replace(n[i], std::regex("_"), "\\_") + "}";
        if (x.is_equal(s.q[i])) return base;
        if (x.is_equal(s.qd[i])) return "\\dot{" + base + "}";
        if (x.is_equal(s.qdd[i])) return "\\ddot{" + base + "}";
        if (x.is_equal(s.p[i])) return "p_{" + base + "}";
    }
    return x.get_TeX_name();
}

const std::vector<std::string>& known_functions() {
    static const std::vector<std::string> f{"sin",  "cos",   "tan",  "asin", "acos",
                                            "atan", "atan2", "sinh", "cosh", "tanh",
                                            "exp",  "log",   "sqrt", "abs",  "pow"};
    return f;
}

std::string reserved_reason(const std::string& name, const angle_convention& c) {
    static const std::vector<std::string> state{
        "phi",      "theta",      "psi",      "phi_dot", "theta_dot", "psi_dot",
        "phi_ddot", "theta_ddot", "psi_ddot", "p_phi",   "p_theta",   "p_psi",
        "omega1",   "omega2",     "omega3",   "t",       "energy"};
    if (std::find(state.begin(), state.end(), name) != state.end())
        return "it names a coordinate, rate, momentum or output";
    for (const auto& q : c.names)
        if (name == q || name == q + "_dot" || name == q + "_ddot" || name == "p_" + q)
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
    for (const auto& q : c.names)
        if (name == "sin_" + q || name == "cos_" + q) return "it is used by the generated code";
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
