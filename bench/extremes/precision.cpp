// Precision: the same scene in float, double and long double, for bench/extremes/precision.sh.
// The checked-in body-form kernels of the free asymmetric top
// (generated/free_asymmetric_top_body.hpp, y = omega, I = (1, 2, 3)) integrated by the runtime
// (runtime/rotgen.hpp) in each scalar type from omega(0) = (1, 0.1, 0.5) over t in [0, 100]
// (about 6.7 periods of omega), against the exact solution (runtime/exact_free_top.hpp) in long
// double. Printed, as Markdown rows: per integrator setting and type, max |omega - exact| over 1001
// samples (max |E(t)/E(0) - 1| in brackets), or
// "-" where the tolerance is below 10 eps of the type (the runtime refuses it). The fixed-step
// driver stops with step_size_underflow when h < 16 eps t (time itself would lose the step).
#include "free_asymmetric_top_body.hpp"
#include <exact_free_top.hpp>
#include <rotgen.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace model = rotgen::models::free_asymmetric_top_body;
using real = long double;

struct outcome {
    real error = 0, energy = 0;
    std::size_t steps = 0;
    bool ok = true;
    real stopped_at = 0;
    std::string why;
};

template <class T, class Method> outcome run(const Method& method) {
    const rotgen::free_top_exact<real> exact({1, 2, 3}, {1, real(T(0.1)), real(T(0.5))});
    auto sys = ROTGEN_GENERATED_SYSTEM_WITH_ENERGY(model, T);
    rotgen::state_vector<T, decltype(sys)> y;
    y << T(1), T(0.1), T(0.5);
    const T e0 = sys.energy(T(0), y.data());
    std::vector<T> times(1001);
    for (std::size_t i = 0; i < times.size(); ++i)
        times[i] = T(100) * T(i) / T(1000);
    outcome o;
    const auto r = rotgen::integrate(sys, method, T(0), y, times, [&](T t, const auto& s) {
        const auto e = exact(real(t));
        for (int j = 0; j < 3; ++j)
            o.error = std::max(o.error, std::abs(real(s[j]) - e[j]));
        o.energy = std::max(o.energy, std::abs(real(sys.energy(t, s.data())) / real(e0) - 1));
    });
    o.steps = r.stats.steps;
    o.ok = r.ok();
    o.stopped_at = real(r.t);
    o.why = rotgen::status_name(r.code);
    return o;
}

std::string cell(const outcome& o) {
    char buf[64];
    if (!o.ok) {
        std::snprintf(buf, sizeof buf, "stops at t = %.4Lg: %s", o.stopped_at, o.why.c_str());
        return buf;
    }
    std::snprintf(buf, sizeof buf, "%.1Le (%.0Le)", o.error, o.energy);
    return buf;
}

template <class T> std::string rk4_cell(double h) {
    rotgen::rk4<T> m;
    m.step = T(h);
    return cell(run<T>(m));
}

template <class T> std::string dop853_cell(double rtol) {
    if (rtol < 10 * std::numeric_limits<T>::epsilon()) return "-";
    rotgen::dop853<T> m{T(rtol), T(rtol * 1e-2)};
    m.max_steps = 10000000;
    return cell(run<T>(m));
}

int main() {
    for (double h : {1e-1, 1e-2, 1e-3, 1e-4})
        std::printf("| rk4 h %g (%.0f steps) | %s | %s | %s |\n", h, 100 / h,
                    rk4_cell<float>(h).c_str(), rk4_cell<double>(h).c_str(),
                    rk4_cell<long double>(h).c_str());
    for (double rtol : {1e-4, 2e-6, 1e-8, 1e-11, 1e-14, 1e-17})
        std::printf("| dop853 rtol %g, atol rtol/100 | %s | %s | %s |\n", rtol,
                    dop853_cell<float>(rtol).c_str(), dop853_cell<double>(rtol).c_str(),
                    dop853_cell<long double>(rtol).c_str());
}
