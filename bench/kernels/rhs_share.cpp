// Where the heavy top's rhs spends its time: the whole rhs (generated/heavy_top.hpp, prepared
// parameters), its one sine-cosine pair alone, and its arithmetic alone (the same statements with
// sin(theta) and cos(theta) given: checked against the rhs to the last bit at every state). ns per
// call, CPU time of the thread, over 256 random states (independent calls: throughput), the median
// of 21 interleaved rounds. Run by bench/kernels/rhs_share.sh.
#include "generated/heavy_top.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <random>
#include <vector>

namespace m = rotgen::models::heavy_top;

namespace {

double cpu_seconds() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// generated/heavy_top.hpp's rhs, its statements as emitted, with sin(theta) and cos(theta) given
__attribute__((noinline)) void arithmetic(const double* y, double sin_theta, double cos_theta,
                                          double* dydt, const m::prepared<double>& p) {
    using S = double;
    const double phi_dot = y[3], theta_dot = y[4], psi_dot = y[5];
    const double t000 = cos_theta * phi_dot;
    const double t001 = p.I3 * psi_dot;
    const double t002 = S(1) / sin_theta;
    const double t003 = p.c001 * t002;
    const double t004 = p.c002 * t000;
    const double t005 = (S(2) * t004 + t001) * cos_theta * t003 -
                        (cos_theta * cos_theta * p.c004 * t002 + sin_theta) * phi_dot;
    dydt[0] = phi_dot;
    dydt[1] = theta_dot;
    dydt[2] = psi_dot;
    dydt[3] = (p.c000 * t000 + t001) * t003 * theta_dot;
    dydt[4] = (p.c003 - (t001 + t004) * phi_dot) * p.c001 * sin_theta;
    dydt[5] = -t005 * theta_dot;
}

__attribute__((noinline)) void rhs(const double* y, double* dydt, const m::prepared<double>& p) {
    m::rhs(0.0, y, dydt, p);
}

__attribute__((noinline)) void sine_cosine(const double* y, double* out) {
    ::sincos(y[1], &out[0], &out[1]); // glibc's, which the rhs calls (GCC joins its sin and cos)
}

template <class F> double ns_per_call(F f) {
    const double t0 = cpu_seconds();
    for (int pass = 0; pass < 200; ++pass)
        for (int i = 0; i < 256; ++i)
            f(i);
    return (cpu_seconds() - t0) * 1e9 / (200.0 * 256);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

} // namespace

int main() {
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(0.3, 1.3); // theta away from 0 and pi
    std::vector<double> y(6 * 256), s(256), c(256);
    for (double& v : y)
        v = u(rng);
    for (int i = 0; i < 256; ++i)
        s[i] = std::sin(y[6 * i + 1]), c[i] = std::cos(y[6 * i + 1]);
    const m::prepared<double> p = m::prepare(m::params<double>{});
    double out[6], check[6];
    for (int i = 0; i < 256; ++i) {
        rhs(&y[6 * i], out, p);
        arithmetic(&y[6 * i], s[i], c[i], check, p);
        if (std::memcmp(out, check, sizeof out) != 0) {
            std::printf("rhs_share: the arithmetic differs from the rhs at state %d\n", i);
            return 1;
        }
    }
    std::vector<double> whole, pair, rest;
    for (int round = 0; round < 21; ++round) {
        whole.push_back(ns_per_call([&](int i) {
            rhs(&y[6 * i], out, p);
            asm volatile("" : : "r"(out) : "memory");
        }));
        pair.push_back(ns_per_call([&](int i) {
            sine_cosine(&y[6 * i], out);
            asm volatile("" : : "r"(out) : "memory");
        }));
        rest.push_back(ns_per_call([&](int i) {
            arithmetic(&y[6 * i], s[i], c[i], out, p);
            asm volatile("" : : "r"(out) : "memory");
        }));
    }
    const double w = median(whole), sc = median(pair), a = median(rest);
    std::printf("| the rhs | %.1f | 1 |\n| its sine and cosine alone | %.1f | %.2f |\n"
                "| its arithmetic alone (28 operations) | %.1f | %.2f |\n",
                w, sc, sc / w, a, a / w);
}
