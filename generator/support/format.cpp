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
    char buf[32]; // "%.17g", without printf's cost (a sweep writes a few per member)
    const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 17);
    return std::string(buf, r.ptr);
}

std::string short_number(double x, int digits) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    return buf;
}

std::string format_duration(double seconds) {
    // the unit: the largest whose value rounds to 1.00 or more (999.7 ms is "1.00 s")
    double v = seconds < 0 || !(seconds == seconds) ? 0 : seconds;
    const char* unit = "s";
    if (v < 0.9995) v *= 1e3, unit = "ms";
    if (v < 0.9995 && unit[0] == 'm') v *= 1e3, unit = "us";
    const int decimals = v >= 99.95 ? 0 : v >= 9.995 ? 1 : v >= 0.9995 ? 2 : 3;
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*f %s", decimals, v, unit);
    return buf;
}

} // namespace rotgen
