// rotgen bench: number formatting.
#include "bench/numbers.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace rotgen::bench {

// shared with simulate: to be replaced by support/'s number formatting (ld_literal ... tol_text)
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
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

std::string short_number(double x, int digits) {
    if (std::isnan(x)) return "";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    return buf;
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
