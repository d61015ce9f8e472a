// rotgen — the forms of the equations of motion a model can be written in (forms.hpp).
#pragma once

namespace rotgen {

// rotor: a linear rotor's two angles (forms/rotor.cpp); rotor_x: the same in the chart whose pole
// is the x axis, which a run near the first chart's pole continues in (not chosen by name).
enum class form_kind { lagrangian, hamiltonian, reduced, body, rotor, rotor_x };

// "lagrangian", "hamiltonian", "reduced", "body", "rotor": the names scene files and the CLI use
// ("rotor_x" for the second chart of the rotor).
const char* to_string(form_kind f);

} // namespace rotgen
