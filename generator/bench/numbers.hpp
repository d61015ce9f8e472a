// rotgen bench: how numbers are written (C++ literals, CSV cells, tables) and GiNaC values read
// into long double.
#pragma once

#include "expr/numbers.hpp"

#include <ginac/ginac.h>

#include <string>

namespace rotgen::bench {

// bench's own: long double literals, table cells (empty for NaN); the rest is support/format.hpp
std::string ld_literal(long double x); // "1.5L", "2.0L": a long double C++ literal, 21 digits
std::string ld_plain(long double x);   // 21 significant digits, no suffix
std::string plain(double x);           // 17 significant digits: reads back to the same double
std::string short_number(double x, int digits = 3); // "" for NaN
std::string csv_number(double x);                   // 6 digits, "" unless finite
std::string tol_text(double x);                     // "1e-09" -> "1e-9"

// scoped_digits and to_long_double: expr/numbers.hpp

} // namespace rotgen::bench
