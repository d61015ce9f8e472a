// rotgen — inertia/: the stability of a gyrostat's steady spin (inertia.hpp, gyrostat_stability).
//
// Spin omega about principal axis s (moments I_j, I_k across it) with wheel momentum h along s.
// Euler's equations with the wheels, I omega_dot + omega x (I omega + h) = 0 (h constant in the
// body), linearised about omega e_s: with (j, k, s) cyclic,
//   I_j d_j' = -((I_s - I_k) omega + h) d_k,   I_k d_k' = ((I_s - I_j) omega + h) d_j,
// so d_j'' = -Omega^2 d_j with
//   Omega^2 = (I_s + h/omega - I_j)(I_s + h/omega - I_k) omega^2 / (I_j I_k):
// stable (an oscillation at Omega) when the product is positive, exponential growth when it is
// negative, i.e. for h/omega strictly between min(I_j, I_k) - I_s and max(I_j, I_k) - I_s. With
// h = 0 this is (5.94) and (5.100); I excludes the wheels' axial moments J a a^T.
#include "inertia/gyrostat.hpp"
#include "inertia/inertia_detail.hpp"

#include "expr/numbers.hpp"

namespace rotgen {

std::array<gyrostat_band, 3> gyrostat_stability(const principal_axes& principal,
                                                const GiNaC::exmap& defaults) {
    const auto& m = principal.moment_values;
    std::array<gyrostat_band, 3> bands;
    for (int s = 0; s < 3; ++s) {
        const int j = (s + 1) % 3, k = (s + 2) % 3;
        const int lo = m[j] <= m[k] ? j : k, hi = lo == j ? k : j;
        gyrostat_band& b = bands[static_cast<std::size_t>(s)];
        b.axis = s + 1;
        b.low = canonical_fraction(principal.moments[lo] - principal.moments[s], defaults);
        b.high = canonical_fraction(principal.moments[hi] - principal.moments[s], defaults);
        b.low_value = m[lo] - m[s];
        b.high_value = m[hi] - m[s];
    }
    return bands;
}

} // namespace rotgen
