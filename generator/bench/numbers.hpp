// rotgen bench: how numbers are written (C++ literals, CSV cells, tables) and GiNaC values read
// into long double.
#pragma once

#include <ginac/ginac.h>

#include <string>

namespace rotgen::bench {

// shared with simulate: to be replaced by support/'s number formatting
std::string ld_literal(long double x); // "1.5L", "2.0L": a long double C++ literal, 21 digits
std::string ld_plain(long double x);   // 21 significant digits, no suffix
std::string plain(double x);           // 17 significant digits: reads back to the same double
std::string short_number(double x, int digits = 3); // "" for NaN
std::string csv_number(double x);                   // 6 digits, "" unless finite
std::string tol_text(double x);                     // "1e-09" -> "1e-9"

// GiNaC's Digits set for the lifetime of this object, restored afterwards (also on an exception).
class scoped_digits {
  public:
    explicit scoped_digits(long digits) : m_saved(GiNaC::Digits) { GiNaC::Digits = digits; }
    scoped_digits(const scoped_digits&) = delete;
    scoped_digits& operator=(const scoped_digits&) = delete;
    ~scoped_digits() { GiNaC::Digits = m_saved; }

  private:
    long m_saved;
};

// GiNaC value -> long double, through its decimal text (callers set Digits = 30); throws
// std::logic_error unless it evaluates to a real number.
long double to_long_double(const GiNaC::ex& e);

} // namespace rotgen::bench
