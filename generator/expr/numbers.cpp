#include "expr/numbers.hpp"

#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rotgen {

GiNaC::numeric exact_rational(double x) {
    if (!std::isfinite(x))
        throw std::domain_error("exact_rational: " + std::to_string(x) + " is not a finite number");
    if (x == 0) return 0;
    // x = m 2^e with 1/2 <= |m| < 1 (frexp normalises subnormals too), and m 2^53 is an integer
    // below 2^53 in magnitude: x = (m 2^53) 2^(e - 53) with no rounding anywhere.
    int e = 0;
    const double m = std::frexp(x, &e);
    const auto mantissa = static_cast<long long>(std::ldexp(m, 53));
    return GiNaC::numeric(mantissa) * GiNaC::numeric(2).power(e - 53);
}

GiNaC::numeric float_numeric(double x) {
    return GiNaC::ex_to<GiNaC::numeric>(exact_rational(x).evalf());
}

long double to_long_double(const GiNaC::ex& e) {
    const GiNaC::ex v = GiNaC::evalf(e);
    if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
        throw std::logic_error("expression did not evaluate to a real number");
    std::ostringstream os;
    os << v;
    return std::stold(os.str());
}

// [+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?, matched by hand: libstdc++'s std::regex
// recurses once per character and overflows the stack on a long scalar.
bool is_decimal(const std::string& s) {
    std::size_t i = 0;
    const auto digits = [&] {
        const std::size_t from = i;
        while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
            ++i;
        return i - from;
    };
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    std::size_t mantissa = digits();
    if (i < s.size() && s[i] == '.') {
        ++i;
        mantissa += digits();
    }
    if (mantissa == 0) return false;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        ++i;
        if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
        if (digits() == 0) return false;
    }
    return i == s.size();
}

} // namespace rotgen
