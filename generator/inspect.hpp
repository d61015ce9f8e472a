// rotgen — `rotgen inspect`: the derived equations as text, LaTeX or JSON.
//
// The JSON form is a contract (DESIGN.md "Interfaces"): model, parameters, coordinates, kinetic,
// potential, lagrangian, momenta[3], mass_matrix[3][3], euler_lagrange[3] (each = 0),
// hamiltonian, hamilton_equations {qdot[3], pdot[3]}, cyclic, energy. Expressions are SymPy-parsable.
#pragma once

#include "derive.hpp"
#include "spec.hpp"

#include <string>

namespace rotgen {

enum class output_format { text, latex, json };

std::string inspect(const model_spec& spec, const derivation& d, output_format format);

// JSON string literal with escapes.
std::string json_quote(const std::string& s);

} // namespace rotgen
