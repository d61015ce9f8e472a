#include "support/format.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>

namespace rotgen {

void append_double(std::string& out, double x) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, x);
    const std::string_view s(buf, static_cast<std::size_t>(r.ptr - buf));
    out += s;
    if (s.find_first_of(".e") == std::string_view::npos &&
        s.find("inf") == std::string_view::npos && s.find("nan") == std::string_view::npos)
        out += ".0";
}

std::string format_double(double x) {
    std::string s;
    append_double(s, x);
    return s;
}

void append_number(std::string& out, double x) {
    if (std::isnan(x)) { // undefined: a sign would mean nothing ("-nan")
        out += "nan";
        return;
    }
    char buf[32]; // "%.17g", without printf's cost (a sweep writes a few per member)
    const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 17);
    out.append(buf, r.ptr);
}

std::string format_number(double x) {
    std::string s;
    append_number(s, x);
    return s;
}

std::string short_number(double x, int digits) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    return buf;
}

std::string short_wide_number(long double x, int digits) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.*Lg", digits, x);
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
