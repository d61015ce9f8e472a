// rotgen — `rotgen inspect`: the derived equations as text, LaTeX or JSON.
//
// The JSON form is a contract (DESIGN.md "Interfaces"): model, parameters, coordinates, kinetic,
// potential, lagrangian, momenta[3], mass_matrix[3][3], euler_lagrange[3] (each = 0),
// hamiltonian, hamilton_equations {qdot[3], pdot[3]}, cyclic, energy. Expressions are
// SymPy-parsable.
//
// With `with_inertia` (`--inertia`), text and LaTeX show the inertia report alone (tensor,
// principal moments and axes, class, stability of steady rotation: inertia.hpp); JSON is the object
// above plus the key `inertia`: {tensor [3][3], principal_moments [3], principal_axes [3][3] (rows,
// so that A I Aᵀ is diagonal, 5.69), class, stability [3] {axis, stable, rate, kind,
// rate_expression} (per unit spin, rate at the defaults), exact_moments, exact_axes,
// principal_moment_values [3], and with `body:` mass, centre_of_mass [3], pivot [3]}.
#pragma once

#include "derive/derive.hpp"
#include "spec/spec.hpp"

#include <string>

namespace rotgen {

enum class output_format { text, latex, json };

// `symbolic` (`--symbolic`): the stability rates of the inertia report (text and LaTeX) as
// expressions in the parameters with their values; without it a rate that depends on the
// parameters is shown as its value at the defaults alone (with parts the expressions run to
// kilobytes). Plain numbers (9/11) are shown exactly either way; JSON always has both.
std::string inspect(const model_spec& spec, const derivation& d, output_format format,
                    bool with_inertia = false, bool symbolic = false);

// The same for a linear rotor (spec.rotor; derive/rotor.hpp, Example 5.4): its two angles phi,
// theta, the direction of its line, T, V, L, p, M, f, the Euler-Lagrange equations, H and
// Hamilton's equations (JSON: the same keys, with two coordinates, and `direction` [3]).
std::string inspect_rotor(const model_spec& spec, output_format format, bool with_inertia = false,
                          bool symbolic = false);

// The inertia report alone, text or LaTeX (as `inspect` with `with_inertia`): it needs no
// derivation.
std::string inspect_inertia(const model_spec& spec, output_format format, bool symbolic);

// JSON string literal with escapes.
std::string json_quote(const std::string& s);

} // namespace rotgen
