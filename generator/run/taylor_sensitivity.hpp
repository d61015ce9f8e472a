// rotgen — the Taylor method with sensitivities: the Taylor recurrences of the augmented system
// (y, S), S = dy/ds (n x k, row-major after y), from the same Taylor printer (emit/taylor.hpp)
// as the motion's own:
//   y' = f(t, y; P)
//   S' = (d f/d y) S + (d f/d P) dP/ds                       (the variational equations)
// built symbolically (GiNaC's derivatives of the form's rates), lowered as one program (the
// subexpressions of f shared with its derivatives) and printed as the coefficient function of a
// system of n + n k states (heyoka's variational equations are expanded the same way).
//
// dP/ds is known when the code is made for the model's parameters: 1 for the key
// parameters.<that parameter>, else 0 (run/sensitivity_start.cpp: a parameter key holds the
// others, an initial value moves no model parameter); what it cannot know, a form parameter that
// the start gives (the reduced form's cyclic momenta), is an input d[q] of the kernel, filled
// per member (taylor_sensitivity_values).
#pragma once

#include "forms/forms.hpp"
#include "lower/lower.hpp"
#include "scene/scene.hpp"

#include <Eigen/Dense>

#include <cstddef>
#include <string>
#include <vector>

namespace rotgen {

// dP/ds (form parameters x keys) as the kernel takes it: the numbers compiled in, NaN where it is
// the kernel's input d[q] (inputs[q] = (form parameter, key)).
struct augmented_forcing {
    Eigen::MatrixXd compiled;
    struct entry {
        std::size_t parameter, key;
    };
    std::vector<entry> inputs;
};

// The augmented system of `f` for the scene's sensitivity keys.
struct augmented_system {
    std::size_t n = 0, keys = 0;       // the state's size and the keys': n + n keys states
    std::vector<GiNaC::ex> rates;      // f, then S' row-major, in the symbols of `inputs`
    std::vector<program_input> inputs; // y[0 .. n + n keys), p.<name>, d[q], t
    augmented_forcing forcing;
};

// The rates of (y, S) for the scene's keys (its `sensitivities:`, or every state component with
// all_initial).
augmented_system augmented_rates(const scene_spec& scene, const form_expressions& f);

// The source appended to a run's translation unit (after run/kernels.cpp's entry points, whose
// rg_params it uses): in the model's namespace taylor_sensitivity(t, c, order, p, d), and
// extern "C" rotgen_taylor_sensitivity_series() and rotgen_taylor_sensitivity(v, t, c, order),
// v = (the form's parameters, then d). The orders are a loop only: straight-line code for fixed
// orders (the motion's taylor_fixed) ran the heavy top's expansion with 4 keys (212 series) 1.4x
// faster (1.3 against 1.8 ms for t = 0..10 at rtol 1e-12) but took 60 s more of the compiler's
// time (8 s). Throws taylor_unsupported as print_taylor_body.
std::string taylor_sensitivity_source(const augmented_system& a, const std::string& unit,
                                      std::size_t parameters);

// v of rotgen_taylor_sensitivity for a member: its parameter values, then dP/ds at the inputs.
// Throws std::logic_error where the member's dP/ds differs from a number compiled in.
std::vector<double> taylor_sensitivity_values(const augmented_forcing& forcing,
                                              const std::vector<double>& parameters,
                                              const Eigen::MatrixXd& dP);

} // namespace rotgen
