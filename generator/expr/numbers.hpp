// rotgen — GiNaC numbers from doubles.
//
// GiNaC::numeric(double), and GiNaC::ex(double) through it, throw CLN's "floating point underflow"
// on a subnormal double (nonzero, below 2.2e-308 in magnitude): CLN's floats have no subnormals.
// The model and scene parsers refuse subnormal literals, but values computed at run time can be
// subnormal (a rate from a tiny omega, a solve, an eigenvector component). Every conversion of a
// double to a GiNaC number goes through these, which are exact and never throw on a finite value.
#pragma once

#include <ginac/ginac.h>

#include <string>

namespace rotgen {

// The value of a finite double, exactly, as a rational: its integer mantissa times a power of two
// (0.1 -> 3602879701896397/36028797018963968, 2^-1074 -> 1/2^1074). Throws std::domain_error for
// an infinity or a NaN.
GiNaC::numeric exact_rational(double x);

// The same value as a GiNaC float (CLN's floats have an unbounded exponent, so it is exact): what
// GiNaC::numeric(x) gives for a normal x, for a subnormal x too. For numeric evaluation (evalf),
// where a float keeps GiNaC from carrying exact fractions through every operation.
GiNaC::numeric float_numeric(double x);

// Whether `s` is a decimal literal and nothing else:
// [+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)? (YAML's own conversion also accepts ".inf" and
// "nan"; model and scene files do not).
bool is_decimal(const std::string& s);

// A real GiNaC value (evalf'd at the caller's GiNaC::Digits) as a long double, through its decimal
// text; std::logic_error unless it evaluates to a real number.
long double to_long_double(const GiNaC::ex& e);

// GiNaC::Digits set for the lifetime of this object, restored afterwards (also on an exception).
class scoped_digits {
  public:
    explicit scoped_digits(long digits) : m_saved(GiNaC::Digits) { GiNaC::Digits = digits; }
    scoped_digits(const scoped_digits&) = delete;
    scoped_digits& operator=(const scoped_digits&) = delete;
    ~scoped_digits() { GiNaC::Digits = m_saved; }

  private:
    long m_saved;
};

} // namespace rotgen
