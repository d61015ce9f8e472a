// rotgen — spec/: checks on the scalars of a model file (identifiers, decimal numbers) and the
// double-precision evaluation that validation uses (spec_detail.hpp).
#include "spec/spec_detail.hpp"

#include "expr/numbers.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

namespace rotgen::spec_detail {

using GiNaC::ex;

// These two match by hand: libstdc++'s std::regex recurses once per character and overflows the
// stack on a long scalar. An identifier has at most 255 characters (later stages match names
// with std::regex).
bool is_identifier(const std::string& s) {
    const auto word = [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    };
    return !s.empty() && s.size() <= 255 && !std::isdigit(static_cast<unsigned char>(s[0])) &&
           std::all_of(s.begin(), s.end(), word);
}

// A finite decimal number, the whole scalar (YAML's own conversion accepts ".inf" and "nan"); not
// subnormal (below 2.2e-308 in magnitude): GiNaC::numeric(double) throws CLN's underflow exception.
bool parse_number(const std::string& text, double& value) {
    if (!is_decimal(text)) return false;
    value = std::strtod(text.c_str(), nullptr);
    return std::isfinite(value) && std::fpclassify(value) != FP_SUBNORMAL;
}

// The value of e at `values` in double precision, as the generated kernels compute it; NaN when
// it is not a real number. (GiNaC's evalf works in arbitrary precision: on sin(exp(exp(20))) it
// reduces an argument of 2e8 digits modulo pi and runs for minutes.)
double double_value(const ex& e, const GiNaC::exmap& values) {
    using namespace GiNaC;
    if (is_a<numeric>(e))
        return ex_to<numeric>(e).is_real() ? ex_to<numeric>(e).to_double() : std::nan("");
    if (is_a<symbol>(e)) {
        const auto it = values.find(e);
        return it == values.end() || is_a<symbol>(it->second) ? std::nan("")
                                                              : double_value(it->second, values);
    }
    std::vector<double> v;
    for (std::size_t i = 0; i < e.nops(); ++i)
        v.push_back(double_value(e.op(i), values));
    if (is_a<add>(e)) {
        double sum = 0;
        for (double x : v)
            sum += x;
        return sum;
    }
    if (is_a<mul>(e)) {
        double product = 1;
        for (double x : v)
            product *= x;
        return product;
    }
    if (is_a<power>(e)) return std::pow(v[0], v[1]);
    if (is_a<function>(e)) {
        const std::string f = ex_to<function>(e).get_name();
        if (v.size() == 2 && f == "atan2") return std::atan2(v[0], v[1]);
        if (v.size() == 1) {
            const double x = v[0];
            if (f == "sin") return std::sin(x);
            if (f == "cos") return std::cos(x);
            if (f == "tan") return std::tan(x);
            if (f == "asin") return std::asin(x);
            if (f == "acos") return std::acos(x);
            if (f == "atan") return std::atan(x);
            if (f == "sinh") return std::sinh(x);
            if (f == "cosh") return std::cosh(x);
            if (f == "tanh") return std::tanh(x);
            if (f == "exp") return std::exp(x);
            if (f == "log") return std::log(x);
            if (f == "abs") return std::fabs(x);
        }
    }
    // Anything else (pi, a function GiNaC produced while simplifying): evalf, on finite arguments.
    for (double x : v)
        if (!std::isfinite(x)) return std::nan("");
    try {
        const ex r = evalf(e.subs(values));
        if (is_a<numeric>(r) && ex_to<numeric>(r).is_real()) return ex_to<numeric>(r).to_double();
    } catch (const std::exception&) {
    }
    return std::nan("");
}

} // namespace rotgen::spec_detail
