// The timing loop of bench/kernels/hoist.sh: the rhs of one model as emitted before and after
// the hoisting of parameter-only subexpressions, timed in interleaved rounds.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <random>
#include <string>
#include <vector>

struct row {
    std::string unit;
    std::size_t n;
    std::vector<double> states;
    // each: ns per call over the states
    std::function<double()> before, after, after_params;
    std::function<double()> mismatch; // max relative difference of after from before
};

inline double cpu_seconds() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

inline std::vector<double> random_states(std::size_t n, std::size_t count) {
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(0.3, 1.3); // away from theta = 0, pi
    std::vector<double> v(n * count);
    for (double& x : v)
        x = u(rng);
    return v;
}

// ns per call of f over the states, 20 passes.
template <class F> std::function<double()> timer(const row& r, F f) {
    return [&r, f]() {
        std::vector<double> out(r.n);
        const std::size_t count = r.states.size() / r.n;
        const double t0 = cpu_seconds();
        for (int pass = 0; pass < 20; ++pass)
            for (std::size_t i = 0; i < count; ++i) {
                f(&r.states[i * r.n], out.data());
                asm volatile("" : : "r"(out.data()) : "memory");
            }
        return (cpu_seconds() - t0) * 1e9 / (20.0 * static_cast<double>(count));
    };
}

template <class B, class A> std::function<double()> compare(const row& r, B before, A after) {
    return [&r, before, after]() {
        std::vector<double> a(r.n), b(r.n);
        double worst = 0;
        for (std::size_t i = 0; i < r.states.size() / r.n; ++i) {
            before(&r.states[i * r.n], b.data());
            after(&r.states[i * r.n], a.data());
            for (std::size_t k = 0; k < r.n; ++k)
                worst = std::max(worst, std::abs(a[k] - b[k]) / std::max(1.0, std::abs(b[k])));
        }
        return worst;
    };
}

inline row make_row(const char* unit, std::size_t n) {
    row r;
    r.unit = unit;
    r.n = n;
    r.states = random_states(n, 256);
    return r;
}

// The timers of unit u into the row r (which must keep its address: rows reserved).
#define ROTGEN_HOIST_TIMERS(r, u)                                                                  \
    do {                                                                                           \
        namespace b = rotgen::models::u##_before;                                                  \
        namespace a = rotgen::models::u##_after;                                                   \
        const b::params<double> pb{};                                                              \
        const a::params<double> pa{};                                                              \
        const a::prepared<double> q = a::prepare(pa);                                              \
        const auto old = [pb](const double* y, double* f) { b::rhs(0.5, y, f, pb); };              \
        const auto now = [q](const double* y, double* f) { a::rhs(0.5, y, f, q); };                \
        const auto plain = [pa](const double* y, double* f) { a::rhs(0.5, y, f, pa); };            \
        (r).before = timer((r), old);                                                              \
        (r).after = timer((r), now);                                                               \
        (r).after_params = timer((r), plain);                                                      \
        (r).mismatch = compare((r), old, now);                                                     \
    } while (0)

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

inline void report(std::vector<row>& rows, int rounds) {
    for (const row& r : rows)
        if (const double m = r.mismatch(); !(m <= 1e-13)) {
            std::fprintf(stderr, "hoist: %s: after differs from before by %.3g\n", r.unit.c_str(),
                         m);
            std::exit(1);
        }
    std::vector<std::vector<double>> tb(rows.size()), ta(rows.size()), tp(rows.size());
    for (int k = 0; k < rounds; ++k)
        for (std::size_t i = 0; i < rows.size(); ++i) {
            tb[i].push_back(rows[i].before());
            ta[i].push_back(rows[i].after());
            tp[i].push_back(rows[i].after_params());
        }
    std::printf(
        "| rhs | before ns | after ns (prepared) | after / before | after, given params ns | "
        "that / before |\n|---|---:|---:|---:|---:|---:|\n");
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const double b = median(tb[i]), a = median(ta[i]), p = median(tp[i]);
        std::printf("| %s | %.1f | %.1f | %.3f | %.1f | %.3f |\n", rows[i].unit.c_str(), b, a,
                    a / b, p, p / b);
    }
}
