// rotgen — the forms of the equations of motion a model can be written in (forms.hpp).
#pragma once

namespace rotgen {

enum class form_kind { lagrangian, hamiltonian, reduced, body };

// "lagrangian", "hamiltonian", "reduced", "body": the names scene files and the CLI use.
const char* to_string(form_kind f);

} // namespace rotgen
