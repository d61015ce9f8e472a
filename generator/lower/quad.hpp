// rotgen — a lowered program (lower.hpp) evaluated in quad precision: __float128, a 113-bit
// significand (about 34 significant digits), with GCC's libquadmath for the functions.
//
// What a sweep member's start needs (run/quad_start.hpp): its initial momenta and angular velocity
// to well beyond long double, from exact decimals, in a few microseconds and without GiNaC, whose
// evaluation at 30 digits takes tens of microseconds and the process-wide lock.
//
// Each operation rounds once to quad (round to nearest), in the program's order: a product of n
// factors over m divisors makes n + m - 1 roundings, a sum one per term and one per coefficient
// other than 1 and -1. Numbers are the program's exact rationals rounded once to quad; pi is
// M_PIq. Only the nodes the outputs reach are evaluated.
//
// Built only where the compiler has __float128 and libquadmath (ROTGEN_HAVE_QUADMATH: GCC on
// x86-64); elsewhere run/quad_start.hpp falls back to GiNaC.
#pragma once

#ifdef ROTGEN_HAVE_QUADMATH

#include "lower/lower.hpp"

#include <cstddef>
#include <utility>
#include <vector>

namespace rotgen {

using quad = __float128;

// A number in quad, rounded once: an integer numerator and denominator of up to 113 bits are
// converted exactly and divided; longer ones go through 40 significant digits.
quad to_quad(const GiNaC::numeric& n);

class quad_program {
  public:
    // Throws std::logic_error for a call libquadmath has no function for.
    explicit quad_program(const lowered_program& program);

    // The number of values evaluate() takes: the program's inputs, in their order.
    std::size_t inputs() const { return m_inputs; }
    // The outputs at `inputs`, in the program's order.
    std::vector<quad> evaluate(const std::vector<quad>& inputs) const;

  private:
    using unary = quad (*)(quad);
    using binary = quad (*)(quad, quad);
    struct instruction {
        lowered_node::kind k = lowered_node::kind::number;
        int input = -1;      // an input's position
        quad value = 0;      // a number's value, a constant's, a sum's constant term
        unary f1 = nullptr;  // a call of one argument
        binary f2 = nullptr; // a call of two
        std::vector<std::pair<quad, int>> terms;
        std::vector<int> numerator, denominator, args;
    };
    quad run(const instruction& in, const std::vector<quad>& v,
             const std::vector<quad>& inputs) const;

    std::size_t m_inputs = 0;
    std::vector<std::pair<int, instruction>>
        m_code; // node, instruction: the reached nodes in order
    std::size_t m_nodes = 0;
    std::vector<int> m_outputs;
};

} // namespace rotgen

#endif
