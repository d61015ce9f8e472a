#include "expr/print.hpp"

#include "expr/angles.hpp"

#include <algorithm>
#include <charconv>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace rotgen {

using GiNaC::ex;
using GiNaC::ex_to;
using GiNaC::is_a;

namespace {

std::string integer_text(const GiNaC::numeric& n) {
    std::ostringstream os;
    os << n;
    return os.str();
}

bool is_negative_power(const ex& f) {
    return is_a<GiNaC::power>(f) && is_a<GiNaC::numeric>(f.op(1)) &&
           ex_to<GiNaC::numeric>(f.op(1)).is_negative();
}

bool has_negative_coefficient(const ex& term) {
    if (is_a<GiNaC::numeric>(term)) return ex_to<GiNaC::numeric>(term).is_negative();
    if (is_a<GiNaC::mul>(term))
        for (std::size_t i = 0; i < term.nops(); ++i)
            if (is_a<GiNaC::numeric>(term.op(i)))
                return ex_to<GiNaC::numeric>(term.op(i)).is_negative();
    return false;
}

// GiNaC holds 1/(a - b) as -1/(b - a) or not, by hash order, which changes from run to run. The
// printers therefore choose the sign of a sum in a denominator themselves: its first term in
// printed order (the coordinates named by c) is made positive. True when `sum` must be negated
// for that.
bool denominator_needs_flip(const ex& sum, const angle_convention& c) {
    std::string first;
    bool negative = false;
    for (std::size_t i = 0; i < sum.nops(); ++i) {
        const ex term = sum.op(i);
        const bool neg = has_negative_coefficient(term);
        const std::string text = text_printer(c)(neg ? ex(-term) : term);
        if (i == 0 || text < first) {
            first = text;
            negative = neg;
        }
    }
    return negative;
}

// True when f is 1/(sum)^n whose sum the printers negate; `odd` tells if the sign changes.
bool flipped_denominator(const ex& f, const angle_convention& c, bool* odd = nullptr) {
    if (is_negative_power(f) && is_a<GiNaC::add>(f.op(0)) &&
        ex_to<GiNaC::numeric>(f.op(1)).is_integer() && denominator_needs_flip(f.op(0), c)) {
        if (odd) *odd = ex_to<GiNaC::numeric>(f.op(1)).is_odd();
        return true;
    }
    return false;
}

bool flips_sign(const ex& f, const angle_convention& c) {
    bool odd = false;
    return flipped_denominator(f, c, &odd) && odd;
}

// A term of a sum, split into sign and magnitude as printed: -3*x -> (true, 3*x).
std::pair<bool, ex> split_sign(const ex& term, const angle_convention& c) {
    bool negative = has_negative_coefficient(term);
    if (is_a<GiNaC::mul>(term)) {
        for (std::size_t i = 0; i < term.nops(); ++i)
            negative ^= flips_sign(term.op(i), c);
    } else {
        negative ^= flips_sign(term, c);
    }
    return {negative, negative ? ex(-term) : term};
}

} // namespace

std::string expression_printer::print(const ex& e, int context) const {
    if (is_a<GiNaC::numeric>(e)) return number(ex_to<GiNaC::numeric>(e), context);
    if (is_a<GiNaC::symbol>(e)) return symbol(ex_to<GiNaC::symbol>(e));
    if (is_a<GiNaC::constant>(e)) return constant(ex_to<GiNaC::constant>(e));
    if (is_a<GiNaC::add>(e)) return sum(e, context);
    if (is_a<GiNaC::mul>(e) || (is_negative_power(e) && is_a<GiNaC::add>(e.op(0))))
        return product(e, context);
    if (is_a<GiNaC::power>(e)) return power(e.op(0), e.op(1), context);
    if (is_a<GiNaC::function>(e)) {
        std::vector<std::string> args;
        for (std::size_t i = 0; i < e.nops(); ++i)
            args.push_back(print(e.op(i), 0));
        return function(function_name(ex_to<GiNaC::function>(e).get_name()), args);
    }
    std::ostringstream os;
    os << e;
    throw std::logic_error("rotgen printer: cannot print expression '" + os.str() + "'");
}

std::string expression_printer::number(const GiNaC::numeric& n, int context) const {
    if (!n.is_real()) throw std::logic_error("rotgen printer: complex number");
    std::string s;
    if (n.is_integer()) {
        s = integer_text(n);
    } else if (n.is_rational()) {
        s = fraction(integer_text(n.numer()), integer_text(n.denom()));
        if (context >= 2) s = parenthesise(s);
        return s;
    } else {
        s = format_double(n.to_double());
    }
    if (n.is_negative() && context >= 2) s = parenthesise(s);
    return s;
}

std::string expression_printer::symbol(const GiNaC::symbol& s) const {
    return display_name(s, angles());
}

std::string expression_printer::constant(const GiNaC::constant& c) const {
    if (ex(c).is_equal(GiNaC::Pi)) return "pi";
    std::ostringstream os;
    os << ex(c);
    throw std::logic_error("rotgen printer: unknown constant " + os.str());
}

std::string expression_printer::sum(const ex& e, int context, bool negate) const {
    std::vector<std::pair<std::string, bool>> terms;
    for (std::size_t i = 0; i < e.nops(); ++i) {
        const auto [negative, magnitude] = split_sign(e.op(i), angles());
        terms.emplace_back(print(magnitude, 1), negative != negate);
    }
    std::sort(terms.begin(), terms.end());
    std::string s;
    for (std::size_t i = 0; i < terms.size(); ++i) {
        if (i == 0)
            s = terms[i].second ? "-" + terms[i].first : terms[i].first;
        else
            s += (terms[i].second ? " - " : " + ") + terms[i].first;
    }
    return context >= 2 || (context == 1 && terms.front().second) ? parenthesise(s) : s;
}

std::string expression_printer::product(const ex& e, int context) const {
    GiNaC::numeric coeff = 1;
    std::vector<std::string> num, den;
    const std::size_t count = is_a<GiNaC::mul>(e) ? e.nops() : 1;
    for (std::size_t i = 0; i < count; ++i) {
        const ex f = is_a<GiNaC::mul>(e) ? e.op(i) : e;
        if (flipped_denominator(f, angles())) {
            // 1/(sum)^n printed as (-1)^n / (-sum)^n, the negated sum's terms printed negated.
            const int n = -ex_to<GiNaC::numeric>(f.op(1)).to_int();
            if (n % 2) coeff = -coeff;
            den.push_back(integer_power(parenthesise(sum(f.op(0), 0, true)), n));
            continue;
        }
        if (is_a<GiNaC::numeric>(f)) {
            coeff *= ex_to<GiNaC::numeric>(f);
        } else if (is_negative_power(f)) {
            den.push_back(print(GiNaC::pow(f.op(0), -f.op(1)), 2));
        } else {
            num.push_back(print(f, 2));
        }
    }
    const bool negative = coeff.is_negative();
    if (negative) coeff = -coeff;
    if (!coeff.is_real()) throw std::logic_error("rotgen printer: complex coefficient");
    if (!coeff.is_rational()) {
        num.insert(num.begin(), number(coeff, 2));
    } else {
        if (!coeff.numer().is_equal(1)) num.insert(num.begin(), integer_text(coeff.numer()));
        if (!coeff.denom().is_equal(1)) den.insert(den.begin(), integer_text(coeff.denom()));
    }
    std::sort(num.begin() +
                  (num.empty() || !std::isdigit(static_cast<unsigned char>(num[0][0])) ? 0 : 1),
              num.end());
    std::sort(den.begin() +
                  (den.empty() || !std::isdigit(static_cast<unsigned char>(den[0][0])) ? 0 : 1),
              den.end());
    const auto join = [&](const std::vector<std::string>& v) {
        std::string s;
        for (std::size_t i = 0; i < v.size(); ++i)
            s += (i ? times() : "") + v[i];
        return s;
    };
    std::string s = num.empty() ? "1" : join(num);
    if (!den.empty()) s = fraction(s, den.size() == 1 && times() == "*" ? den[0] : join(den));
    if (negative) s = "-" + s;
    return (negative && context >= 1) || (!den.empty() && context >= 3) ? parenthesise(s) : s;
}

// True when s is one parenthesised group: "(a + b)" but not "(a)*(b)".
static bool is_wrapped(const std::string& s) {
    if (s.size() < 2 || s.front() != '(' || s.back() != ')') return false;
    int depth = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        depth += s[i] == '(' ? 1 : s[i] == ')' ? -1 : 0;
        if (depth == 0 && i + 1 < s.size()) return false;
    }
    return true;
}

std::string expression_printer::fraction(const std::string& num, const std::string& den) const {
    const bool simple = den.find_first_of("*/+- ") == std::string::npos || is_wrapped(den);
    return num + "/" + (simple ? den : parenthesise(den));
}

std::string expression_printer::integer_power(const std::string& base, int n) const {
    return n == 1 ? base : base + "**" + std::to_string(n);
}

std::string latex_printer::integer_power(const std::string& base, int n) const {
    return n == 1 ? base : base + "^{" + std::to_string(n) + "}";
}

std::string expression_printer::power(const ex& base, const ex& exponent, int context) const {
    if (exponent.is_equal(GiNaC::numeric(1, 2))) return function("sqrt", {print(base, 0)});
    std::string s = print(base, 3) + "**" + print(exponent, 3);
    return context >= 3 ? parenthesise(s) : s;
}

std::string expression_printer::function(const std::string& name,
                                         const std::vector<std::string>& args) const {
    std::string s = name + "(";
    for (std::size_t i = 0; i < args.size(); ++i)
        s += (i ? ", " : "") + args[i];
    return s + ")";
}

// ---- LaTeX ----

std::string latex_printer::number(const GiNaC::numeric& n, int context) const {
    if (n.is_rational() && !n.is_integer()) {
        const std::string s = fraction(integer_text(n.numer()), integer_text(n.denom()));
        return n.is_negative() && context >= 1 ? "\\left(" + s + "\\right)" : s;
    }
    return expression_printer::number(n, context);
}

std::string latex_printer::symbol(const GiNaC::symbol& s) const {
    const std::string tex = display_tex_name(s, angles());
    if (!tex.empty() && tex != s.get_name()) return tex;
    // Parameters: trailing digits become a subscript, multi-letter names upright.
    static const std::regex with_index("([A-Za-z]+)_?([0-9]+)");
    std::smatch m;
    const std::string name = s.get_name();
    if (std::regex_match(name, m, with_index)) return m[1].str() + "_{" + m[2].str() + "}";
    if (name.size() == 1) return name;
    static const std::vector<std::string> greek{"alpha", "beta",   "gamma", "delta", "epsilon",
                                                "kappa", "lambda", "mu",    "nu",    "rho",
                                                "sigma", "tau",    "omega", "Omega", "eta"};
    if (std::find(greek.begin(), greek.end(), name) != greek.end()) return "\\" + name;
    std::string escaped;
    for (char c : name)
        escaped += c == '_' ? std::string("\\_") : std::string(1, c);
    return "\\mathrm{" + escaped + "}";
}

std::string latex_printer::constant(const GiNaC::constant& c) const {
    if (ex(c).is_equal(GiNaC::Pi)) return "\\pi";
    return expression_printer::constant(c);
}

std::string latex_printer::power(const ex& base, const ex& exponent, int context) const {
    if (exponent.is_equal(GiNaC::numeric(1, 2))) return "\\sqrt{" + print(base, 0) + "}";
    // sin^2(theta) style for functions
    if (is_a<GiNaC::function>(base) && is_a<GiNaC::numeric>(exponent) &&
        ex_to<GiNaC::numeric>(exponent).is_pos_integer()) {
        const std::string f = print(base, 0);
        const auto paren = f.find("\\left(");
        if (f[0] == '\\' && paren != std::string::npos)
            return f.substr(0, paren) + "^{" + print(exponent, 0) + "}" + f.substr(paren);
    }
    std::string b = print(base, 3);
    if (b.find("\\frac") == 0) b = "\\left(" + b + "\\right)";
    const std::string s = b + "^{" + print(exponent, 0) + "}";
    return context >= 3 ? "\\left(" + s + "\\right)" : s;
}

std::string latex_printer::function(const std::string& name,
                                    const std::vector<std::string>& args) const {
    static const std::vector<std::string> known{"sin",  "cos",  "tan",    "exp",    "log",   "sinh",
                                                "cosh", "tanh", "arcsin", "arccos", "arctan"};
    std::string head;
    if (name == "sqrt") return "\\sqrt{" + args.at(0) + "}";
    if (name == "abs") return "\\left|" + args.at(0) + "\\right|";
    if (name == "asin" || name == "acos" || name == "atan")
        head = "\\arc" + name.substr(1);
    else if (std::find(known.begin(), known.end(), name) != known.end())
        head = "\\" + name;
    else
        head = "\\operatorname{" + name + "}";
    std::string s = head + "\\left(";
    for (std::size_t i = 0; i < args.size(); ++i)
        s += (i ? ", " : "") + args[i];
    return s + "\\right)";
}

std::string latex_printer::fraction(const std::string& num, const std::string& den) const {
    return "\\frac{" + num + "}{" + den + "}";
}

std::string to_text(const ex& e, const angle_convention& angles) {
    return text_printer(angles)(e);
}
std::string to_latex(const ex& e, const angle_convention& angles) {
    return latex_printer(angles)(e);
}

} // namespace rotgen
