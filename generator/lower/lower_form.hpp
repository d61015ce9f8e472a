// rotgen — lowering of a whole form: the stage value the emitter prints.
//
// A form (forms/forms.hpp) plus what was asked of it (the outputs, the parameters to fold into
// the code) become one lowered_program per generated function:
//
//   * the outputs: the names given, checked, in output_names()' fixed order; none given: rhs,
//     jacobian and every other output the form can give;
//   * specialisation: the folded parameters are substituted by the exact rationals their defaults
//     stand for (exact_decimal); the same candidates are also lowered with the parameters as
//     inputs and folded afterwards (lower_folded), which keeps the runtime program's sharing;
//   * candidate choice: of several equivalent candidates (form_output::alternatives,
//     form_expressions::alternative_rates), the cheapest after lowering, an operation weighted by
//     its rough cost in cycles (+-* 1, / 4, a call 20); the first of equals;
//   * the Jacobian's structural zeros: an entry exactly 0 by any route, or one that vanishes
//     identically (evaluated at fixed pseudo-random points with 40 digits), is 0 in every
//     candidate; with both rhs and jacobian asked, rhs_and_jacobian shares their work.
#pragma once

#include "forms/forms.hpp"
#include "lower/lower.hpp"
#include "spec/spec.hpp"

#include <string>
#include <vector>

namespace rotgen {

// What the generated code is asked to give.
struct kernel_request {
    std::vector<std::string> outputs;    // empty: every output the form can give
    bool specialise_all = false;         // fold every model parameter into the code
    std::vector<std::string> specialise; // or these
    // `--sensitivities`: parameters.<name> keys; parameter_jacobian and variational_rhs for them
    std::vector<std::string> sensitivities{};
};

// One generated function, lowered.
struct lowered_function {
    // rhs, jacobian, rhs_and_jacobian, energy, momenta, mass_matrix, omega, rotation,
    // ignored_rates, parameter_jacobian, variational_rhs
    std::string name;
    lowered_program program; // its inputs: the state (y[i]), the run-time parameters (p.name), t
    // targets[i] receives output i: "dydt[0]", "J[7]", "momentum[2]", or "return".
    std::vector<std::string> targets;
    // The function's arguments, those that may go unused: t, y, p.
    std::vector<std::string> arguments;
    std::vector<std::string> entry_names; // one per output, for documentation (form_output::names)
};

struct lowered_form {
    form_kind form = form_kind::lagrangian;
    lagrangian_strategy strategy = lagrangian_strategy::explicit_inverse;
    std::vector<std::string> state_names;
    std::vector<std::string> rate_names;
    std::vector<std::string> notes; // the form's documentation (form_expressions::notes)
    std::vector<form_parameter> runtime_parameters; // the parameters the code takes at run time
    std::vector<std::string> folded;                // the folded ones, "I1 = 1.5"
    // Row-major state_size x state_size: true where the Jacobian is structurally zero; empty
    // without a Jacobian.
    std::vector<bool> jacobian_zero;
    std::vector<lowered_function> functions; // in output order (rhs_and_jacobian after jacobian)
    // With sensitivities: the parameters of d f/d p, in the order asked (k of them), and where
    // d f/d y (n x n) and d f/d p (n x k) are structurally zero, and where d f/d y is exactly 1
    // (d q_dot/d q_dot), row-major. parameter_jacobian writes dfdp[i * k + j]; variational_rhs's
    // program gives dydt[i], then the other d f/d y and the non-zero d f/d p entries as locals
    // `const T dfdy_i_m`, `const T dfdp_i_j`, from which the emitter writes
    // dSdt = (d f/d y) S + [0 | d f/d p].
    std::vector<std::string> sensitivity_names;
    std::vector<bool> sensitivity_dfdy_zero, sensitivity_dfdy_one, sensitivity_dfdp_zero;
    // The parameter-only subexpressions hoisted out of rhs, jacobian and rhs_and_jacobian (of the
    // run-time parameters), each once for the form: prepare() computes them per parameter set,
    // the functions read them as p.c000, ... Each is printed with the program it was found in.
    struct constant {
        std::size_t function; // index in `functions`
        int node;             // in that function's program
        std::string name;     // p.c000
    };
    std::vector<constant> constants;
};

// Checks the names of `request.outputs` (user_error "unknown output ..." with a suggestion), then
// builds the form, with the orientation kept (the body form's quaternion, for a free body too)
// when "rotation" is asked: what a caller of lower_form() builds first.
form_expressions build_requested_form(const model_spec& spec, const derivation& d, form_kind form,
                                      lagrangian_strategy strategy, const kernel_request& request);

// Lowers the functions `request` asks of the form `f` (built for `spec`). Throws user_error for an
// unknown output, one the form cannot give, an unknown parameter name in `specialise`, or a bad
// sensitivity key (not parameters.<model parameter>, folded by `specialise`, given twice, or
// asked with the taylor output) (messages start "rotgen emit: ..."); std::logic_error for
// internal failures.
lowered_form lower_form(const model_spec& spec, const form_expressions& f,
                        const kernel_request& request);

// The exact rational a parameter default stands for: the shortest decimal that reads back as the
// double (9.81 -> 981/100), so that folded constants are exact in every scalar type.
GiNaC::numeric exact_decimal(double x);

} // namespace rotgen
