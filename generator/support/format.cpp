#include "support/format.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace rotgen {

std::string format_double(double x) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, x);
    std::string s(buf, r.ptr);
    if (s.find_first_of(".e") == std::string::npos && s.find("inf") == std::string::npos &&
        s.find("nan") == std::string::npos)
        s += ".0";
    return s;
}

std::string format_number(double x) {
    if (std::isnan(x)) return "nan"; // undefined: a sign would mean nothing ("-nan")
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

std::string short_number(double x, int digits) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    return buf;
}

} // namespace rotgen
