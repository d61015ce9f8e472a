// rotgen — the expression language of model and scene files.
//
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := primary (('^' | '**') unary)?          (right-associative)
//   primary := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'
//
// Numbers become exact rationals (0.5 -> 1/2, 9.81 -> 981/100) so that the derivation is exact and
// its printed form deterministic. Functions: sin cos tan asin acos atan atan2 sinh cosh tanh exp
// log sqrt abs pow; the constant pi. Every error names the column of the offending token.
#pragma once

#include "support/error.hpp"

#include <ginac/ginac.h>

#include <map>
#include <string>

namespace rotgen {

// The names an expression may use and what they stand for.
using name_table = std::map<std::string, GiNaC::ex>;

// Parses `text`; `where` locates its first character, `what` names it in messages ("potential").
// Throws user_error (unknown name, syntax error, division by zero, wrong argument count).
GiNaC::ex parse_expression(const std::string& text, const name_table& names,
                           const source_location& where, const std::string& what);

} // namespace rotgen
