// rotgen — inspect/: the derived equations as the printers take them (inspect.cpp), whatever the
// number of coordinates: a top's three Euler angles (derive.hpp) or a linear rotor's two angles
// (derive/rotor.hpp, Example 5.4).
#pragma once

#include "derive/derive.hpp"
#include "expr/angles.hpp"
#include "expr/symbols.hpp"
#include "spec/spec.hpp"

#include <ginac/ginac.h>

#include <string>
#include <vector>

namespace rotgen {

struct equations {
    angle_convention angles;        // the model's: the names the printers show the symbols by
    std::vector<std::string> names; // the coordinates: phi, theta[, psi]
    std::vector<GiNaC::ex> q, p;    // their symbols and their momenta's (for LaTeX)
    std::string coordinates_note;   // the text's "coordinates:" line
    std::string latex_note;         // the LaTeX comment line below the title
    std::vector<GiNaC::ex> omega;   // body angular velocity (5.30); none for a rotor
    std::vector<GiNaC::ex>
        direction; // a rotor's line in space axes (third row of A); none for a top
    GiNaC::ex kinetic, potential, lagrangian, hamiltonian, energy;
    std::vector<GiNaC::ex> momenta, forcing, euler_lagrange, qdot, pdot; // one per coordinate
    std::vector<std::vector<GiNaC::ex>> mass_matrix;
    std::vector<int> cyclic; // indices into names
};

// What a derivation with n coordinates (the first n of the angles, named by `angles`; symbols q,
// momenta's symbols p) gives every model: a top's `derivation` or a rotor's `rotor_derivation`.
template <class Derivation>
equations equations_of(const Derivation& d, std::size_t n, const std::vector<GiNaC::ex>& q,
                       const std::vector<GiNaC::ex>& p, const angle_convention& angles) {
    equations e;
    e.angles = angles;
    for (std::size_t i = 0; i < n; ++i) {
        e.names.push_back(angles.names[i]);
        e.q.push_back(q[i]);
        e.p.push_back(p[i]);
        e.momenta.push_back(d.momenta[i]);
        e.forcing.push_back(d.forcing[i]);
        e.euler_lagrange.push_back(d.euler_lagrange[i]);
        e.qdot.push_back(d.hamilton_qdot[i]);
        e.pdot.push_back(d.hamilton_pdot[i]);
        e.mass_matrix.emplace_back(d.mass_matrix[i].begin(), d.mass_matrix[i].end());
    }
    e.kinetic = d.kinetic, e.potential = d.potential, e.lagrangian = d.lagrangian;
    e.hamiltonian = d.hamiltonian, e.energy = d.energy;
    e.cyclic = d.cyclic;
    return e;
}

// A linear rotor's equations in its first chart (derive_rotor(spec, 1)).
equations rotor_equations(const model_spec& spec);

} // namespace rotgen
