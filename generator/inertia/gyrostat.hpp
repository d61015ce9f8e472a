// rotgen — inertia/: the stability of a gyrostat's steady spin (gyrostat.cpp).
#pragma once

#include "inertia/inertia.hpp"

namespace rotgen {

// A gyrostat (inertia/gyrostat.cpp): spin omega about principal axis s with wheel momentum h
// along it is stable when (I_s + h/omega - I_j)(I_s + h/omega - I_k) > 0, unstable for h/omega
// strictly between low = min(I_j, I_k) - I_s and high = max(I_j, I_k) - I_s.
struct gyrostat_band {
    int axis = 0;
    GiNaC::ex low, high;
    double low_value = 0, high_value = 0; // at the defaults
};
std::array<gyrostat_band, 3> gyrostat_stability(const principal_axes& principal,
                                                const GiNaC::exmap& defaults);

} // namespace rotgen
