// rotgen — emission: the one C++ printer of lowered programs (lower/lower.hpp).
//
// A program prints as its temporaries, `const T t000 = <definition>;` in order, then its outputs,
// each in terms of inputs and temporaries. The printer sorts the terms of a sum and the factors of
// a product by their text (the same bytes every run); it flattens an inline product into its
// parent's factors, multiplies a number into an inline sum where that costs no multiplication
// (c (a x + b y) -> (c a) x + (c b) y, exact) and absorbs a negation into a sum
// (-(x - y) -> y - x). Numbers print as exact rationals of the scalar type, `S(1)/S(3)`, folded by
// the compiler. lowered_program::after counts the operations of exactly this text (lowering counts
// them without printing; print_body_checked() checks that the two agree).
//
// The inline mode prints every node at its use: no temporaries at all, sin and cos not hoisted.
// It is the "unlowered" code of the work-precision bench: the same factored expressions, none of
// their sharing.
#pragma once

#include "forms/forms.hpp"
#include "lower/lower.hpp"

#include <string>
#include <vector>

namespace rotgen {

// C++ text of a node as used in an expression: temporaries and inputs by name, anything else
// inline; `scalar` names the type of literals (`S(1)/S(3)`, folded by the compiler).
std::string print_node(const lowered_program& program, int node, const std::string& scalar = "S");

// The expression a node stands for (a temporary's right-hand side).
std::string print_definition(const lowered_program& program, int node,
                             const std::string& scalar = "S");

// A number as printed in expressions: `S(2)`, `S(1)/S(3)`, `-S(2)`.
std::string print_number(const GiNaC::numeric& value, const std::string& scalar = "S");

// The operations (+ - * / and calls) of the program as print_node/print_definition print it:
// its temporaries plus its outputs. Equal to program.after.
op_count printed_op_count(const lowered_program& program);

// The operations of one node's definition as print_definition prints it.
op_count definition_op_count(const lowered_program& program, int node);

// The operations of the program's hoisted constants (lowered_program::constants): what prepare()
// computes once, and what a call given params<T> computes first.
op_count constants_op_count(const lowered_program& program);

// The program's outputs with no temporaries: `<indent><targets[i]> = <output i>;` a line, every
// node printed where it is used (a node used twice is printed twice), sin/cos not hoisted. An
// output that is a bare number is wrapped as T(...) (inside a function templated on T).
std::string print_outputs_inline(const lowered_program& program,
                                 const std::vector<std::string>& targets,
                                 const std::string& scalar = "S",
                                 const std::string& indent = "    ");

// The rates of a form, the numbers in `folded` substituted (symbol -> exact number), lowered and
// printed inline as `dydt[i] = ...;` lines: the body of an unlowered rhs(t, y, dydt, p). The state
// prints as y[i], the run-time parameters as p.<name>, time as t; literals as `scalar`(...).
std::string print_rhs_inline(const form_expressions& f, const GiNaC::exmap& folded = {},
                             const std::string& scalar = "T");

} // namespace rotgen
