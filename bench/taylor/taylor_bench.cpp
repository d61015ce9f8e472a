// The Taylor method against rotgen's DOP853: time to reach an error, on the free top and the heavy
// top, t = 0..100, with the checked-in generated headers (generated/*_taylor.hpp). Run by
// bench/taylor/taylor.sh, which writes bench/results/taylor.md.
//
// Each configuration: the error at t = 100 (max-norm over the state) against the reference (free
// top: the exact elliptic solution in long double; heavy top: DOP853 in long double at rtol
// 2e-18, checked against the Taylor method in long double at 2e-19), and the wall time, the
// median of 7 timed loops of at least 20 ms each. Time to reach an error: the fastest
// configuration of the tolerance sweep (half decades) whose error is at most that.
#include "rotgen.hpp"

#include "exact_free_top.hpp"

#include "free_asymmetric_top_body_taylor.hpp"
#include "heavy_top_taylor.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace rotgen;
namespace free_top = rotgen::models::free_asymmetric_top_body_taylor;
namespace heavy_top = rotgen::models::heavy_top_taylor;

namespace {

// The orders of the tolerance sweep (1e-6 .. 1e-15 in half decades) as straight-line code, as
// `rotgen simulate` compiles the orders of its scene's tolerances.
#define TAYLOR_ORDERS 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19

struct point {
    double tol, error, seconds;
    std::size_t steps;
    int order;
};

// Median seconds of one call of f (7 loops of >= 20 ms).
template <class F> double median_time(F&& f) {
    using clock = std::chrono::steady_clock;
    int calls = 1;
    for (;;) {
        const auto a = clock::now();
        for (int i = 0; i < calls; ++i)
            f();
        const double s = std::chrono::duration<double>(clock::now() - a).count();
        if (s > 0.02) break;
        calls *= 2;
    }
    std::vector<double> t;
    for (int r = 0; r < 7; ++r) {
        const auto a = clock::now();
        for (int i = 0; i < calls; ++i)
            f();
        t.push_back(std::chrono::duration<double>(clock::now() - a).count() / calls);
    }
    std::sort(t.begin(), t.end());
    return t[3];
}

template <class Sys, class Method, class Vec, class Ref>
point measure(const Sys& sys, Method m, double tol, const Vec& y0, const Ref& ref) {
    m.rtol = m.atol = tol;
    Vec y = y0;
    const auto res = integrate(sys, m, 0.0, y, 100.0);
    point p{tol, 0, 0, res.stats.steps, 0};
    for (Eigen::Index i = 0; i < y.size(); ++i)
        p.error = std::max(p.error, double(std::abs((long double)y[i] - ref[i])));
    p.seconds = median_time([&] {
        Vec z = y0;
        integrate(sys, m, 0.0, z, 100.0);
        if (!(z[0] == z[0])) std::abort();
    });
    return p;
}

std::vector<double> sweep(double from, double to) {
    std::vector<double> v;
    for (double e = from; e <= to + 1e-9; e += 0.5)
        v.push_back(std::pow(10.0, -e));
    return v;
}

double time_to(const std::vector<point>& pts, double target) {
    double best = -1;
    for (const auto& p : pts)
        if (p.error <= target && (best < 0 || p.seconds < best)) best = p.seconds;
    return best;
}

std::string us(double s) {
    if (s < 0) return "not reached";
    char b[32];
    std::snprintf(b, sizeof b, "%.1f us", s * 1e6);
    return b;
}

template <class Sys, class Vec, class Ref, class RhsSys>
void report(const char* title, const Sys& sys, const RhsSys& rhs_sys, const Vec& y0,
            const Ref& ref) {
    std::vector<point> tay, dop;
    for (double tol : sweep(6, 15)) {
        point p = measure(sys, taylor<double>(), tol, y0, ref);
        p.order = taylor<double>::order_for(tol); // rtol = atol: the same order either control
        tay.push_back(p);
    }
    for (double tol : sweep(6, 14.5))
        dop.push_back(measure(rhs_sys, dop853<double>(), tol, y0, ref));
    std::printf("### %s\n\n", title);
    std::printf("| error at t = 100 | DOP853 (best rtol) | Taylor (best tol) | speed-up |\n");
    std::printf("|---|---:|---:|---:|\n");
    for (double target : {1e-8, 1e-10, 1e-12, 1e-13, 1e-14}) {
        const double a = time_to(dop, target), b = time_to(tay, target);
        char r[32] = "-";
        if (a > 0 && b > 0) std::snprintf(r, sizeof r, "%.1fx", a / b);
        std::printf("| %.0e | %s | %s | %s |\n", target, us(a).c_str(), us(b).c_str(), r);
    }
    std::printf("\n| tol | Taylor: order | steps | mean step | error | time | DOP853: steps | "
                "error | time |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (std::size_t i = 0; i < tay.size(); ++i) {
        const point& t = tay[i];
        std::printf("| %.1e | %d | %zu | %.3f | %.1e | %s |", t.tol, t.order, t.steps,
                    100.0 / double(t.steps), t.error, us(t.seconds).c_str());
        if (i < dop.size())
            std::printf(" %zu | %.1e | %s |\n", dop[i].steps, dop[i].error,
                        us(dop[i].seconds).c_str());
        else
            std::printf(" | | |\n");
    }
    std::printf("\n");
}

} // namespace

int main() {
    {
        const std::array<long double, 3> w0 = {1, 0.1L, 0.5L};
        const free_top_exact<long double> exact({1, 2, 3}, w0);
        const auto e = exact(100.0L);
        const Eigen::Vector3d y0(1, 0.1, 0.5);
        report("Free asymmetric top, I = (1, 2, 3), omega(0) = (1, 0.1, 0.5), body form (omega)",
               ROTGEN_GENERATED_TAYLOR_SYSTEM_ORDERS(free_top, double, TAYLOR_ORDERS),
               ROTGEN_GENERATED_SYSTEM_RHS(free_top, double), y0, e);
    }
    {
        using vec = Eigen::Matrix<double, 6, 1>;
        using lvec = Eigen::Matrix<long double, 6, 1>;
        const vec y0 = (vec() << 0.1, 0.5, 0.2, 0.3, 0.1, 10.0).finished();
        dop853<long double> d;
        d.rtol = d.atol = 2e-18L;
        lvec ref = y0.cast<long double>();
        integrate(ROTGEN_GENERATED_SYSTEM_RHS(heavy_top, long double), d, 0.0L, ref, 100.0L);
        taylor<long double> t;
        t.rtol = t.atol = 2e-19L;
        lvec check = y0.cast<long double>();
        integrate(ROTGEN_GENERATED_TAYLOR_SYSTEM(heavy_top, long double), t, 0.0L, check, 100.0L);
        report("Heavy top, Lagrangian form, (phi, theta, psi) = (0.1, 0.5, 0.2), rates (0.3, 0.1, "
               "10)",
               ROTGEN_GENERATED_TAYLOR_SYSTEM_ORDERS(heavy_top, double, TAYLOR_ORDERS),
               ROTGEN_GENERATED_SYSTEM_RHS(heavy_top, double), y0, ref);
        std::printf("(heavy-top reference: DOP853 and Taylor in long double agree to %.1Le)\n\n",
                    (ref - check).cwiseAbs().maxCoeff());
    }
}
