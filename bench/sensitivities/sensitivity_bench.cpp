// The cost of sensitivities: S = dy(t)/ds of the heavy top by three routes, at the same accuracy of
// S, on the emitted kernels (`rotgen emit --sensitivities`) with rotgen's runtime:
//   variational  DOP853 on variational_rhs (y and S, n x (n + k), in one kernel)
//   differences  central differences of 2k + 1 DOP853 runs of rhs (step h = tol^(1/3) |s|)
//   cvodes       SUNDIALS CVODES forward sensitivities (Adams with fixed-point iteration, or with
//                Newton, the dense solver and the emitted jacobian; staggered, S in the error
//                test), fS from the emitted jacobian and parameter_jacobian, only the key columns
// at tolerances 1e-5 .. 1e-13 (atol = rtol / 100), t = 0..10, a nutating top (0.1, 0.5, 0, 0.3,
// 0.2, 10). The error of S: the largest |S - S_ref| / max(1e-3, max |S_ref| of its column) over
// the key columns, S_ref from variational_rhs at rtol 1e-14. Time: the median of 7 runs (wall
// clock). Built and run by bench/sensitivities/run.sh, which writes the table as Markdown rows.
#include "heavy_top_k1.hpp"
#include "heavy_top_k11.hpp"
#include "heavy_top_k4.hpp"

#include <rotgen.hpp>

#include "cvodes_route.hpp"
#include "sensitivity_unit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr double t_end = 10;
const std::vector<double> y0{0.1, 0.5, 0.0, 0.3, 0.2, 10.0};

ROTGEN_SENSITIVITY_UNIT(k1, heavy_top_k1)
ROTGEN_SENSITIVITY_UNIT(k4, heavy_top_k4)
ROTGEN_SENSITIVITY_UNIT(k11, heavy_top_k11)

template <class U> double& parameter(typename U::P& p, std::size_t i) {
    return reinterpret_cast<double*>(&p)[i]; // params<double> is parameter_count doubles
}

// y(t_end) by DOP853 on rhs, from y_start with parameters p.
template <class U>
std::vector<double> run(const std::vector<double>& y_start, const typename U::P& p, double rtol) {
    auto sys = rotgen::make_system<double, U::n>(
        [&](double t, const double* y, double* f) { U::rhs(t, y, f, p); });
    rotgen::state_vector<double, decltype(sys)> y;
    for (std::size_t i = 0; i < U::n; ++i)
        y[static_cast<Eigen::Index>(i)] = y_start[i];
    rotgen::integrate(sys, rotgen::dop853<double>(rtol, rtol / 100), 0.0, y, t_end);
    return std::vector<double>(y.data(), y.data() + U::n);
}

// S(t_end) for the key columns (state columns first when `initial`) by central differences of
// 2k + 1 runs (the nominal run too, as a user of differences needs y).
template <class U> std::vector<double> differences(double rtol, bool initial) {
    constexpr std::size_t n = U::n, nk = U::n + U::k;
    std::vector<double> S(n * nk, 0.0);
    const typename U::P nominal{};
    run<U>(y0, nominal, rtol);
    for (std::size_t c = initial ? 0 : n; c < nk; ++c) {
        std::vector<double> yp = y0, ym = y0;
        typename U::P pp = nominal, pm = nominal;
        double* s = c < n ? nullptr : &parameter<U>(pp, U::parameter_index(c - n));
        const double value = c < n ? y0[c] : *s;
        const double h = std::cbrt(rtol) * std::max(1.0, std::abs(value));
        if (c < n) {
            yp[c] += h;
            ym[c] -= h;
        } else {
            *s += h;
            parameter<U>(pm, U::parameter_index(c - n)) -= h;
        }
        const std::vector<double> a = run<U>(yp, pp, rtol), b = run<U>(ym, pm, rtol);
        for (std::size_t i = 0; i < n; ++i)
            S[i * nk + c] = (a[i] - b[i]) / (2 * h);
    }
    return S;
}

// The largest error of the key columns against the reference (inf for a failed run).
template <class U>
double error_of(const std::vector<double>& S, const std::vector<double>& ref, bool initial) {
    constexpr std::size_t n = U::n, nk = U::n + U::k;
    if (S.size() != ref.size()) return HUGE_VAL; // the run failed: printed as inf
    double worst = 0;
    for (std::size_t c = initial ? 0 : n; c < nk; ++c) {
        double scale = 1e-3, e = 0;
        for (std::size_t i = 0; i < n; ++i) {
            scale = std::max(scale, std::abs(ref[i * nk + c]));
            e = std::max(e, std::abs(S[i * nk + c] - ref[i * nk + c]));
        }
        worst = std::max(worst, e / scale);
    }
    return worst;
}

template <class F> double median_seconds(F&& f) {
    std::vector<double> t;
    for (int r = 0; r < 7; ++r) {
        const auto start = std::chrono::steady_clock::now();
        f();
        t.push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

// One row per route and tolerance: keys | route | rtol | ms | error of S.
template <class U> void rows(const char* keys, bool initial) {
    const std::vector<double> ref = sensitivity_routes::variational<U>(y0, t_end, 1e-14);
    for (double rtol = 1e-5; rtol > 1e-13 * 0.5; rtol /= 10) {
        std::vector<double> S;
        double s = median_seconds([&] { S = sensitivity_routes::variational<U>(y0, t_end, rtol); });
        std::printf("| %s | variational | %.0e | %.3f | %.1e |\n", keys, rtol, 1e3 * s,
                    error_of<U>(S, ref, initial));
        s = median_seconds([&] { S = differences<U>(rtol, initial); });
        std::printf("| %s | differences | %.0e | %.3f | %.1e |\n", keys, rtol, 1e3 * s,
                    error_of<U>(S, ref, initial));
        for (const bool newton : {false, true}) {
            s = median_seconds(
                [&] { S = cvodes_route::sensitivities<U>(y0, t_end, rtol, initial, newton); });
            std::printf("| %s | cvodes %s | %.0e | %.3f | %.1e |\n", keys,
                        newton ? "newton" : "fixed-point", rtol, 1e3 * s,
                        error_of<U>(S, ref, initial));
        }
    }
}

} // namespace

int main() {
    rows<k1>("h (k = 1)", false);
    rows<k4>("h, I3, M, g (k = 4)", false);
    rows<k11>("6 initial + 5 parameters (k = 11)", true);
}
