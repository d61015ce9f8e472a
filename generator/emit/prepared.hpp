// rotgen — emission: prepared<T> and prepare(), the parameters with the form's hoisted constants
// (lowered_form::constants, lower/lower_form.hpp) computed once per parameter set.
#pragma once

#include "lower/lower_form.hpp"

#include <string>

namespace rotgen {

// The struct prepared<T> (params<T> plus one member per constant) and prepare(params), printed
// from templates/prepared.hpp.in; every header has them (with no constants, prepared<T> is
// params<T> under another name).
std::string prepared_text(const lowered_form& form);

} // namespace rotgen
