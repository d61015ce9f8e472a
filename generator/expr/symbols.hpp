// rotgen — the one symbol table.
//
// GiNaC identifies symbols by object, not by name: a second realsymbol("theta") is a different
// symbol and differentiating by it silently gives 0. Every stage therefore takes the coordinate,
// velocity, acceleration, momentum and time symbols from here.
//
// Convention: Euler angles z-x-z (phi about z, theta about the new x, psi about the new z),
// phi, psi in [0, 2 pi), theta in [0, pi]; theta = 0, pi is the coordinate singularity.
#pragma once

#include <ginac/ginac.h>

#include <array>
#include <string>
#include <vector>

namespace rotgen {

struct coordinate_symbols {
    std::array<GiNaC::realsymbol, 3> q;     // phi, theta, psi
    std::array<GiNaC::realsymbol, 3> qd;    // phi_dot, theta_dot, psi_dot
    std::array<GiNaC::realsymbol, 3> qdd;   // phi_ddot, theta_ddot, psi_ddot
    std::array<GiNaC::realsymbol, 3> p;     // p_phi, p_theta, p_psi
    std::array<GiNaC::realsymbol, 3> omega; // omega1, omega2, omega3 (body frame)
    GiNaC::realsymbol t;
};

// The process-wide symbols (created once, on first use).
const coordinate_symbols& symbols();

struct angle_convention; // expr/angles.hpp: the model's sequence and the angles' names

// Names a model may not use for a parameter, with the reason ("a coordinate", "a GiNaC constant",
// ...); empty when the name is free. The angles' names are c's (and always phi, theta, psi).
std::string reserved_reason(const std::string& name, const angle_convention& c);

// Functions the expression language knows, as written in model files.
const std::vector<std::string>& known_functions();

} // namespace rotgen
