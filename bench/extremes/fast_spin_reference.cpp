// The reference for bench/extremes/fast_spin.sh: the heavy top (generated/heavy_top.hpp, the
// Lagrangian form checked in from models/heavy_top.yaml) with g = 10 (so M g h / I1 = 1),
// released at theta0 = 0.5 with phi_dot = theta_dot = 0 and psi_dot = omega3, integrated in long
// double by dop853 at rtol 1e-17. Prints phi(T) and the range of theta over the samples in
// [T/2, T] (1001 samples over [0, T]), 21 significant digits.
//   fast_spin_reference OMEGA3 T
#include "heavy_top.hpp"
#include <rotgen.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace model = rotgen::models::heavy_top;

int main(int argc, char** argv) {
    using T = long double;
    if (argc != 3) {
        std::fprintf(stderr, "usage: fast_spin_reference OMEGA3 T\n");
        return 2;
    }
    const T omega3 = std::strtold(argv[1], nullptr), t_end = std::strtold(argv[2], nullptr);
    auto sys = ROTGEN_GENERATED_SYSTEM(model, T);
    sys.params.g = 10;
    rotgen::state_vector<T, decltype(sys)> y;
    y << 0, T(0.5), 0, 0, 0, omega3;
    rotgen::dop853<T> method(T(1e-17), T(1e-19));
    method.max_steps = 100000000;
    std::vector<T> times(1001);
    for (std::size_t i = 0; i < times.size(); ++i)
        times[i] = t_end * T(i) / T(times.size() - 1);
    T lo = 10, hi = -10, phi = 0;
    const auto r = rotgen::integrate(sys, method, T(0), y, times, [&](T t, const auto& s) {
        if (t >= t_end / 2) lo = std::min(lo, s[1]), hi = std::max(hi, s[1]);
        phi = s[0];
    });
    if (!r.ok()) {
        std::fprintf(stderr, "fast_spin_reference: %s\n", r.message.c_str());
        return 1;
    }
    std::printf("%.21Lg %.21Lg %.21Lg %zu\n", phi, lo, hi, r.stats.rhs_evals);
}
