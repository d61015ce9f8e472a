// rotgen bench: number formatting.
#include "bench/numbers.hpp"

#include "support/format.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace rotgen::bench {

// long double literals and table cells; doubles as support/format.hpp writes them
std::string ld_literal(long double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.21LgL", x);
    std::string s = buf;
    if (s.find_first_of(".eEn") == std::string::npos) s.insert(s.size() - 1, ".0");
    return s;
}

std::string ld_plain(long double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.21Lg", x);
    return buf;
}

std::string plain(double x) {
    return format_number(x);
}

std::string short_number(double x, int digits) {
    return std::isnan(x) ? "" : rotgen::short_number(x, digits);
}

std::string csv_number(double x) {
    return std::isfinite(x) ? short_number(x, 6) : "";
}

std::string tol_text(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0e", x);
    std::string s = buf;
    const auto e = s.find("e-0");
    if (e != std::string::npos) s.erase(e + 2, 1);
    const auto p = s.find("e+0");
    if (p != std::string::npos) s.erase(p + 1, 2);
    return s;
}

} // namespace rotgen::bench
