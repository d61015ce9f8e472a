// rotgen — inspect/: a gyrostat's wheels in `rotgen inspect` (wheels.cpp). Each is "" for a
// model without wheels.
#pragma once

#include "inertia/inertia.hpp"
#include "spec/spec.hpp"

#include <string>

namespace rotgen {

// The wheels: axis, J, drive, p_k = J (a . omega + alpha_dot), h, and what T and L mean.
std::string wheels_text(const model_spec& spec);
// The JSON member "wheels" (with a leading ",\n"): [{name, axis, inertia, drive, rate|torque}].
std::string wheels_json(const model_spec& spec);
// --inertia: the thresholds of h/omega per principal axis (inertia/gyrostat.hpp); the JSON
// member "gyrostat_stability" (with a leading ",\n") for the inertia object.
std::string gyrostat_stability_text(const model_spec& spec, const inertia_report& r);
std::string gyrostat_stability_json(const model_spec& spec, const inertia_report& r);

} // namespace rotgen
