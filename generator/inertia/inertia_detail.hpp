// rotgen — inertia/: exact helpers shared by the files of this stage (not part of its interface):
// 3x3 tensor algebra with expanded entries, exact square roots and quotients, and the value of an
// entry at the parameters' defaults.
#pragma once

#include "inertia/inertia.hpp"

namespace rotgen::inertia_detail {

// The value at the defaults, or std::invalid_argument if it is not a finite real number.
double value_or_throw(const GiNaC::ex& e, const GiNaC::exmap& defaults);

// canonical_radicals, then the roots of each term merged again for printing (sqrt(6), not
// sqrt(2)*sqrt(3)).
GiNaC::ex printable_radicals(const GiNaC::ex& e);
// q = n/d, exactly: a polynomial quotient where d divides n, else a canonical fraction.
GiNaC::ex exact_quotient(const GiNaC::ex& n, const GiNaC::ex& d, const GiNaC::exmap& defaults);
// √x for x >= 0, with square factors of a rational x taken out: √(p/q) = s √r / q, pq = s² r.
GiNaC::ex exact_sqrt(const GiNaC::ex& x);

matrix3 zero3();
matrix3 add(const matrix3& a, const matrix3& b);     // a + b, entries expanded
matrix3 scale(const GiNaC::ex& s, const matrix3& a); // s a, entries expanded
matrix3 diagonal(const GiNaC::ex& a, const GiNaC::ex& b, const GiNaC::ex& c);
GiNaC::ex dot(const vector3& a, const vector3& b); // expanded
vector3 cross(const vector3& a, const vector3& b); // expanded

} // namespace rotgen::inertia_detail
