// rotgen — a run continued from the last row of an earlier run's CSV (`simulate --from RUN.csv`).
//
// The row gives the start time and the initial state; the scene gives everything else (the model,
// its parameters, the form, the method, the end time, the number of samples, the records). The
// row must hold a complete state of the scene's form, as recorded columns:
//   lagrangian   phi theta psi phi_dot theta_dot psi_dot
//   hamiltonian  phi theta psi p_phi p_theta p_psi
//   reduced      theta and the momenta p_phi p_theta p_psi, with the angles the form keeps
//   body         q0 q1 q2 q3 omega1 omega2 omega3 (q0..q3 normalised: the attitude, scalar first)
//   rotor        phi theta phi_dot theta_dot
// The CSV's numbers are written with 17 significant digits (support/format.hpp), so a state that
// the CSV holds whole reads back exactly. Line 1, the provenance line (run/provenance.hpp), must
// name the scene's model (its name and the SHA-256 of its file) and the scene's form: a run of
// another model or form is refused there.
#pragma once

#include "forms/forms.hpp"
#include "scene/scene.hpp"

#include <string>

namespace rotgen {

// Reads the last row of `csv` into `scene`: scene.from, the start time, the initial angles and
// rates (as plain numbers). Throws user_error located in the CSV for a file that is not a run's
// CSV, a run of another model or form (at line 1, naming both), a row that lacks a name of the
// form's state (all the missing ones are named), a value that is not a finite number; or at the
// scene's time `end` when it equals the row's time.
void continue_from(scene_spec& scene, const std::string& csv);

// Refuses (user_error at the row) a start row that lacks a state variable of the form `f` or one
// of its conserved momenta (the reduced form's parameters).
void check_start_row(const start_row& row, const form_expressions& f);

// The value of `name` in the row; NaN when the row has no such column.
double row_value(const start_row& row, const std::string& name);

// A gyrostat (run/wheel_start.cpp): each free wheel's momentum p_<wheel> from the row; refused in
// the hamiltonian and reduced forms. Nothing for a model without wheels.
void continue_wheels(scene_spec& scene, const start_row& row);

} // namespace rotgen
