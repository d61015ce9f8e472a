// rotgen bench: the variants of a scene's equations that the bench compares (formulation x code
// generation), and the text the driver receives for each.
//
// Every variant is specialised (parameters folded into the code) and lowered (CSE, hoisted
// trigonometry) unless its label says otherwise:
//   the scene's form                  main: every integrator, scalar type and peer
//   <main>+runtime                    parameters read from params<T> at run time
//   <main>+unlowered                  rhs printed expression by expression, no CSE (explicit
//                                     methods only; the emitter has no switch for this, so the
//                                     text comes from naive_rhs)
//   every other form that applies     lagrangian:explicit, lagrangian:solve, hamiltonian, reduced
//                                     (cyclic coordinates), body:quaternion, body:omega (free body)
#pragma once

#include "bench/initial_state.hpp"
#include "derive/derive.hpp"
#include "emit/emit.hpp"
#include "forms/forms.hpp"
#include "scene/scene.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace rotgen::bench {

enum class role { main, runtime, unlowered, alternative };

struct variant {
    std::string unit, label;
    form_kind form = form_kind::lagrangian;
    lagrangian_strategy strategy = lagrangian_strategy::explicit_inverse;
    bool quaternion = false; // body form: keep the orientation
    bool specialised = true, lowered = true;
    role r = role::alternative;
    bool implicit_runs = false; // the plan runs its implicit methods too
    unsigned double_methods = 0, float_methods = 0, long_double_methods = 0, drift_methods = 0,
             peers = 0; // what the driver compiles for it (bits of harness.hpp)
    form_expressions f;
    std::vector<std::string> outputs;
    emitted_header header;
    std::string naive; // the unlowered rhs (namespace <unit>_naive)
    bool has_A = false, has_energy = false;
};

struct variant_set {
    std::vector<variant> variants;          // [0] is the main variant
    std::optional<std::size_t> hamiltonian; // the long runs' variant, if there is one
};

// "lagrangian:explicit", "hamiltonian", "body:quaternion", ...
std::string form_label(form_kind form, lagrangian_strategy strategy, bool quaternion);

// The variants of the scene (only the main form's three and one other form with `quick`).
// `euler_usable`: the Euler-angle forms can start (sin theta != 0 and the initial rates known);
// `orientation`: needs_orientation(scene, false) (run/engine.hpp, the rule simulate uses);
// `split_form`: the split methods run, so body:quaternion (their form) is among the variants with
// `quick` too. Throws user_error if the scene's own form fails.
variant_set choose_variants(const scene_spec& scene, const model_spec& spec, const derivation& d,
                            bool euler_usable, bool orientation, bool quick, bool split_form);

// The body form with the quaternion, specialised and lowered (the split methods' variant), if any.
std::optional<std::size_t> split_variant(const std::vector<variant>& variants);

// The unlowered rhs: every rate printed on its own by the C printer (no CSE, no hoisting), in
// namespace rotgen::models::<unit>_naive; `folded`: the specialised parameters' values.
std::string naive_rhs(const variant& v, const GiNaC::exmap& folded);

// The struct variant_<index> that bench/workprecision/driver.cpp.in receives for a variant: its
// label, sizes and method bits, parameters and initial state (k), rhs and Jacobian, energy and
// conserved momenta, and the map to the common representation (common_state.hpp).
std::string variant_struct(const variant& v, std::size_t index, const scene_spec& scene,
                           const kinematics& k, const derivation& d);

} // namespace rotgen::bench
