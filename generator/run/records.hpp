// rotgen — run/: recorded quantities that no form holds as a state or an output, built from the
// form's own expressions (README "record"). Conventions: z-x-z Euler angles, passive
// A = Az(psi) Ax(theta) Az(phi) (5.25, body <- space), omega in body axes (5.30), I the inertia
// tensor in body axes (5.39):
//   L1 L2 L3   L_i = sum_j I_ij omega_j, the angular momentum in body axes
//   Lx Ly Lz   L_space = A^T L, the angular momentum in space axes
//   T          1/2 omega . I omega (5.38)
//   V          the potential, so that T + V = energy
// The attitude quaternion q0..q3 is computed at each sample instead (kernels.hpp: source_value).
#pragma once

#include "forms/forms.hpp"
#include "spec/spec.hpp"

#include <array>
#include <optional>
#include <string>

namespace rotgen {

// The expression of `name` (one of the above) in the form's state, time and parameters, or
// nothing when the form does not determine it (the reduced form without omega, or without A).
std::optional<GiNaC::ex> derived_record(const model_spec& spec, const form_expressions& f,
                                        const std::string& name);

// A gyrostat (run/wheel_records.cpp; derive/wheels.hpp), given body omega: the total angular
// momentum I_e omega + h, the total kinetic energy, and h1..h3, <wheel>_dot, p_<wheel>.
std::array<GiNaC::ex, 3> gyrostat_momentum(const model_spec& spec, const std::vector<GiNaC::ex>& w);
GiNaC::ex gyrostat_kinetic(const model_spec& spec, const std::vector<GiNaC::ex>& w);
std::optional<GiNaC::ex> wheel_record(const model_spec& spec, const std::vector<GiNaC::ex>& w,
                                      const std::string& name);

} // namespace rotgen
