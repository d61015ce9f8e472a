// rotgen — the variational (augmented) system of a form, for sensitivities: the state y and
// S = dy/ds (n x k) move together as
//   y' = f(t, y; P),   S' = (d f/d y) S + (d f/d P) D,   D = dP/ds (P x k, constant in a run),
// P the form's parameters (the model's, and the reduced form's cyclic momenta), s the k keys.
//
// variational_system_of() gives the pieces (f, d f/d y, d f/d P) as GiNaC expressions, from the
// same derivatives the Jacobian and the parameter Jacobian use (forms/forms.hpp: for the `solve`
// strategy through M's factors); augmented_rates() writes the n + n k right-hand sides with
// symbols for S and D (for a method that needs the augmented system itself, as Taylor series do).
//
// variational_entry() compiles them for the run (run/sensitivity_run.hpp): one function that
// lowers f and the non-zero entries of d f/d y and d f/d P together, their common subexpressions
// shared, and prints the products with S and D with the structural zeros left out (an entry
// exactly 1, d phi/dt by phi_dot, as no factor), a loop over the k columns that the compiler
// unrolls: no Jacobian multiplied at run time.
#pragma once

#include "forms/forms.hpp"

#include <ginac/ginac.h>

#include <cstddef>
#include <string>
#include <vector>

namespace rotgen {

struct variational_system {
    std::vector<GiNaC::ex> rates; // f, n
    std::vector<GiNaC::ex> dfdy;  // d f/d y, row-major n x n
    std::vector<GiNaC::ex> dfdp;  // d f/d P, row-major n x P (f.parameters' order)
};

// The pieces of the form's variational system. Uses GiNaC: the caller holds symbolic_mutex()
// where one is needed (run/prepared.hpp).
variational_system variational_system_of(const form_expressions& f);

// y' then S' (row-major n x k after y): f_i, then sum_m dfdy_im S_mj + sum_p dfdp_ip D_pj, with
// `S` (n x k) and `D` (P x k) the symbols (or values) to use, row-major.
std::vector<GiNaC::ex> augmented_rates(const variational_system& v, const std::vector<GiNaC::ex>& S,
                                       const std::vector<GiNaC::ex>& D);

// The C++ source of
//   extern "C" void rotgen_variational(const double* v, double t, const double* y, double* out)
// with v = (the form's parameter values, then D row-major P x k), y = (y, S row-major n x k) and
// out = (f, S'), for `keys` = k columns. Depends on <cmath> alone.
std::string variational_entry(const form_expressions& f, std::size_t keys);

} // namespace rotgen
