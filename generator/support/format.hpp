// rotgen — numbers as text, the same way everywhere (CSV, summaries, headers, messages).
#pragma once

#include <string>

namespace rotgen {

// The shortest decimal that reads back as the same double, with a ".0" on integers ("9.81",
// "1e-10", "3.0"): for generated code, headers and messages that quote a value.
std::string format_double(double x);

// 17 significant digits (printf "%.17g"): every double round-trips; the CSV number format.
std::string format_number(double x);

// format_double(x) and format_number(x) appended to `out`, without a string of their own (a
// sweep's summary rows are built from a few dozen each).
void append_double(std::string& out, double x);
void append_number(std::string& out, double x);

// `digits` significant digits (printf "%.<digits>g"): for summaries, tables and messages (never
// "%f", which shows 1e-8 as 0.000000).
std::string short_number(double x, int digits = 3);
// The same for a long double, which may lie beyond double's range ("1.19e+4932").
std::string short_wide_number(long double x, int digits = 3);

// A duration in the one unit that fits, three significant digits, never an exponent: "1.30 s",
// "14.8 ms", "507 us" (ASCII "us"; summaries print "time    <number> <s|ms|us> <what>" and
// scripts read it). Seconds of 1000 and more stay in s ("1300 s").
std::string format_duration(double seconds);

} // namespace rotgen
