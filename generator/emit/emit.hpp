// rotgen — stage 5: emission. A lowered form (lower/lower_form.hpp) becomes one C++ header. The
// emitter prints: it never builds or lowers a form (emit/printer.hpp prints each program).
//
// The header's skeleton is templates/*.in (embedded at build time by cmake/embed_templates.cmake);
// this module fills their @placeholders@ and writes only the pieces that were asked for.
//
// The generated header (the contract the runtime and `rotgen simulate` rely on):
//
//   file      <unit>.hpp, unit = <model name> for the Lagrangian form and <model name>_<form> for
//   the
//             others (heavy_top.hpp, heavy_top_hamiltonian.hpp, heavy_top_reduced.hpp,
//             heavy_top_body.hpp), so that every form of a model can live in one directory and one
//             translation unit; `--name` chooses another unit (two variants of one form);
//   namespace rotgen::models::<unit>;
//   template <class T> struct params { T <parameter> = <default>; ... };  (empty if all folded)
//   template <class T> struct prepared : params<T> { T c000, ...; };  prepare(params) fills it:
//     the parameter-only subexpressions of rhs, jacobian and rhs_and_jacobian, computed once
//     (lowered_form::constants); those three take prepared<T> or params<T> (prepared at the call);
//   constexpr model_name, form_name, state_size, state_names, parameter_count, parameter_names;
//   per requested output:
//     template <class T> void rhs(T t, const T* y, T* dydt, const params<T>& p);
//     template <class T> void jacobian(T t, const T* y, T* J, const params<T>& p);  (row-major)
//       + constexpr jacobian_pattern, and rhs_and_jacobian(t, y, dydt, J, p) when both are asked;
//     template <class T> T energy(const T* y, const params<T>& p);
//     template <class T> void momenta(const T* y, T* momentum, const params<T>& p);   (3)
//     template <class T> void mass_matrix(const T* y, T* M, const params<T>& p);      (3x3)
//     template <class T> void omega(const T* y, T* w, const params<T>& p);            (3)
//     template <class T> void rotation(const T* y, T* A, const params<T>& p);         (3x3, 5.25)
//     template <class T> void ignored_rates(const T* y, T* rates, const params<T>& p); (reduced)
//     template <class T> void taylor(T t, T* c, int order, const params<T>& p);  (taylor.hpp)
//       + constexpr taylor_series, the coefficient blocks it fills
//   body form with a quaternion: quaternion_from_angles(angles, q), angles_from_quaternion(q,
//   angles).
#pragma once

#include "derive/derive.hpp"
#include "emit/printer.hpp"
#include "forms/forms.hpp"
#include "lower/lower.hpp"
#include "lower/lower_form.hpp"
#include "spec/spec.hpp"

#include <string>
#include <vector>

namespace rotgen {

// What the header says about itself and what it is called.
struct header_options {
    std::string command; // the command that regenerates the header (for its comment)
    std::string name;    // the unit (namespace and file stem); empty: unit_name()
};

struct function_stats {
    std::string function;
    op_count before, after;
    std::size_t temporaries = 0;
    op_count hoisted;    // the operations of the constants it reads from prepared<T>
    std::string summary; // when set, the header's description says this instead of the counts
};

struct emitted_header {
    std::string unit;      // the namespace inside rotgen::models, and the file's stem
    std::string file_name; // unit + ".hpp"
    std::string text;
    std::vector<function_stats> stats;
};

// "heavy_top" for the Lagrangian form, "heavy_top_hamiltonian", ... for the others.
std::string unit_name(const std::string& model, form_kind form);

// The header of a lowered form; std::logic_error for internal failures. The caller builds and
// lowers the form:
//   const kernel_request request{outputs, specialise_all, specialise};
//   const form_expressions f = build_requested_form(spec, d, form, strategy, request);
//   const emitted_header h = emit_header(spec, lower_form(spec, f, request), {command, name});
emitted_header emit_header(const model_spec& spec, const lowered_form& form,
                           const header_options& options);

// Fills the @name@ placeholders of templates/<name>; a placeholder without a value is an error.
std::string fill_template(const std::string& name,
                          const std::map<std::string, std::string>& values);

} // namespace rotgen
