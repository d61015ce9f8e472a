// rotgen — emission: the sensitivity kernels parameter_jacobian and variational_rhs (`rotgen emit
// --sensitivities`), from lowered_form's sensitivity fields (lower/lower_form.hpp).
//
// variational_rhs's lowered program gives dydt and the non-zero entries of d f/d y and d f/d p as
// locals (dfdy_i_m, dfdp_i_j); the lines printed here add the product
//   dSdt[i * (n + k) + c] = sum_m dfdy_i_m S[m * (n + k) + c]  (+ dfdp_i_(c - n) for c >= n),
// the structural zeros left out, an entry exactly 1 (d q_dot/d q_dot) as no factor.
#pragma once

#include "lower/lower_form.hpp"

#include <map>
#include <string>
#include <vector>

namespace rotgen {

struct variational_product {
    std::vector<std::string> lines; // `    dSdt[..] = ...;`
    op_count operations;            // theirs
};

// The lines of dSdt = (d f/d y) S + [0 | d f/d p]; `scalar` names the literals' type (a row of
// d f/d y that is all zero gives T(scalar(0)) in the state columns).
variational_product variational_product_lines(const lowered_form& form, const std::string& scalar);

// The placeholders of templates/parameter_jacobian.hpp.in and variational_rhs.hpp.in beyond the
// common ones: k, nk (n + k), keys (h, I3), key_names ("h", "I3").
std::map<std::string, std::string> sensitivity_values(const lowered_form& form);

} // namespace rotgen
