// rotgen — emission: the Taylor printer. A lowered rhs program (lower/lower.hpp) becomes the body
// of `taylor(t, c, order, p)`, which fills the Taylor coefficients of the solution of
// dy/dt = f(t, y) through (t, y) up to a run-time order, by automatic differentiation.
//
// Notation: x^[k] = x^(k)(t) / k!, the k-th normalised derivative, so that
// x(t + h) = sum_k x^[k] h^k. The solution's coefficients follow from y' = f(t, y):
//   y^[k] = f^[k-1] / k,
// and f^[k-1] from the coefficients of lower order of every operation in f, one recurrence per
// operation (Jorba & Zou, Exp. Math. 14 (2005) 99-117, section 2; the same list, derived in full,
// in heyoka's "Notes on automatic differentiation", Biscani & Izzo, MNRAS 504 (2021) 2614):
//   a = sum c_i b_i        a^[k] = sum c_i b_i^[k]
//   a = b c                a^[k] = sum_{j=0..k} b^[j] c^[k-j]                 (Leibniz)
//   a = b / c              a^[k] = (b^[k] - sum_{j=1..k} c^[j] a^[k-j]) / c^[0]
//   s = sin b, c = cos b   s^[k] = 1/k sum_{j=1..k} j b^[j] c^[k-j],
//                          c^[k] = -1/k sum_{j=1..k} j b^[j] s^[k-j]     (one pair per argument)
//   a = exp b              a^[k] = 1/k sum_{j=1..k} j b^[j] a^[k-j]
//   a = log b              a^[k] = (k b^[k] - sum_{j=1..k-1} j a^[j] b^[k-j]) / (k b^[0])
//   a = sqrt b             a^[k] = (b^[k] - sum_{j=1..k-1} a^[j] a^[k-j]) / (2 a^[0])
//   a = b^alpha            a^[k] = sum_{j=0..k-1} (k alpha - j (alpha + 1)) b^[k-j] a^[j]
//                                  / (k b^[0])                          (alpha constant)
//   a = atan2(y, x)        a^[k] = (sum_{j=1..k} j (x^[k-j] y^[j] - y^[k-j] x^[j])
//                                  - sum_{j=1..k-1} j a^[j] r^[k-j]) / (k r^[0]), r = x^2 + y^2
//                          (from a' r = x y' - y x', differentiated k - 1 times)
// Integer powers are products already (lowering's binary powering), x x a square (Leibniz's sum
// folded in half). Subexpressions of parameters and numbers alone are constants, computed once;
// time is the series (t, 1, 0, ...). Every other node of the lowered DAG is one series (its CSE
// carries over); a product of several factors is a chain of binary products.
#pragma once

#include "lower/lower.hpp"

#include <cstddef>
#include <stdexcept>
#include <string>

namespace rotgen {

// A rate the recurrences do not cover; what() names it. The caller locates it: the model file
// (rotgen emit), the scene's integrator (a run).
struct taylor_unsupported : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct taylor_body {
    std::string text;           // the statements of taylor(t, c, order, p)
    std::string fixed_text;     // of taylor_fixed<Order>(t, c, p): the order a constant
    std::size_t series = 0;     // coefficient blocks in c: the state's, then the intermediates'
    std::size_t operations = 0; // recurrences per order (sums, products, calls)
    // at most 8 recurrences per order: each order waits on the last, so taylor_fixed takes
    // operations off that chain (products folded into the rates, the last order's terms apart from
    // the vector sums: templates/taylor_helpers.hpp.in), where a larger system has work enough to
    // hide the wait and pays for the extra operations (the heavy top's 22 took 10-25% more)
    bool few_operations = false;
};

// The body of taylor() for the rhs program `rhs` (its inputs: the state as y[i], the parameters,
// t; its outputs: the rates, in state order). Throws taylor_unsupported for a function the
// recurrences do not cover (tan, asin, abs, ...; pow with a varying exponent).
taylor_body print_taylor_body(const lowered_program& rhs);

} // namespace rotgen
