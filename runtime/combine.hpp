/// \file
/// rotgen runtime — the vector arithmetic of the explicit Runge–Kutta methods.
///
/// Rigid-body states have 3 to 13 components, and for them the integrator's own work costs as much
/// as the generated kernel (the free top's right-hand side is three products). Written as Eigen
/// expressions on member vectors, a DOP853 stage on the free top cost 16 ns against 9.5 ns for a
/// stage of Boost.Odeint's Fehlberg 7(8) on the same kernel: every stage went through memory (the
/// kernel writes through a pointer), partly as 16-byte loads of values just stored as 8-byte
/// scalars, which the CPU cannot forward.
///
/// So the explicit methods keep their stages in `work_vector`s: for a system with a static size a
/// std::array<T, N> in a local variable, which the compiler keeps in registers once the loops below
/// (trip count N, known) are unrolled and the kernel is inlined — as fast as the same step written
/// out by hand in scalar variables (16.7 µs for 242 steps of the free top, both); for a run-time
/// size an Eigen vector held by the stepper. The stages are stored in the stepper only in steps
/// that hold samples (dense output). Free top, DOP853 at tol 1e-10, 2909 evaluations: 46 µs before,
/// 26.5 µs after (bench/workprecision; the README's "Work-precision" section).
///
///   stage(out, y, h, newest, earlier...)   out = y + h·(Σ earlier a_j k_j + a_new k_new)
///   combination(out, terms...)             out = Σ a_j k_j
///   all_finite(v), assign(to, from)
///
/// A stage is evaluated as (y + h·Σ earlier) + (h·a_new)·k_new: everything but the newest stage can
/// be summed while f is still computing it, so the next evaluation of f waits for one multiply and
/// one add only (the compiler may not reassociate floating-point sums itself).
#pragma once

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>

#include "system.hpp"

namespace rotgen::detail {

template <class T, class S>
using work_vector =
    std::conditional_t<(static_state_size<S>() > 0), std::array<T, static_state_size<S>()>,
                       Eigen::Matrix<T, Eigen::Dynamic, 1>>;

// A step is one function body called with either the local or the member array of stages; it
// must be inlined into both calls (ROTGEN_ALWAYS_INLINE), or the local array would be passed by
// address and stay in memory (measured: 33 against 19.6 µs for 242 fixed DOP853 steps). And the
// stepping loop must stay small enough for the compiler to keep the state in registers: what runs
// at most once per integration or only in steps with samples is out of line (ROTGEN_COLD). The
// driver's stepping loops are never inlined into their caller (ROTGEN_NOINLINE): inlined into a
// benchmark loop whose system, state and result lie in one heap object, the stores of the result
// and the state may alias the system's parameters, which then are reloaded after every store
// (measured: DOP853 on the free top with run-time parameters 8.1 against 13.9 µs).
#if defined(__GNUC__) || defined(__clang__)
/// Forces inlining (GCC, Clang); plain `inline` elsewhere. See the comment above.
#define ROTGEN_ALWAYS_INLINE __attribute__((always_inline)) inline
/// Keeps a function out of line and marks it rarely run (GCC, Clang); nothing elsewhere.
#define ROTGEN_COLD __attribute__((noinline, cold))
/// Keeps a function out of line (GCC, Clang); nothing elsewhere.
#define ROTGEN_NOINLINE __attribute__((noinline))
#else
#define ROTGEN_ALWAYS_INLINE inline
#define ROTGEN_COLD
#define ROTGEN_NOINLINE
#endif

/// A work vector of n components, zero.
template <class V> V make_work_vector(std::size_t n) {
    V v{};
    if constexpr (!std::is_aggregate_v<V>) v = V::Zero(static_cast<Eigen::Index>(n));
    return v;
}

template <class V> constexpr std::size_t size_of(const V& v) {
    return static_cast<std::size_t>(v.size());
}

/// One term a·k of a linear combination of stage vectors.
template <class T, class V> struct term {
    T a;
    const V& k;
};

template <class T, class V> term<T, V> make_term(long double a, const V& k) {
    return term<T, V>{T(a), k};
}

template <class T, class V, class... Earlier>
inline void stage(V& out, const V& y, T h, term<T, V> newest, Earlier... earlier) {
    const T h_new = h * newest.a;
    for (std::size_t i = 0; i < size_of(out); ++i) {
        if constexpr (sizeof...(Earlier) == 0)
            out[i] = y[i] + h_new * newest.k[i];
        else
            out[i] = (y[i] + h * (... + (earlier.a * earlier.k[i]))) + h_new * newest.k[i];
    }
}

template <class V, class... Terms> inline void combination(V& out, Terms... terms) {
    for (std::size_t i = 0; i < size_of(out); ++i)
        out[i] = (... + (terms.a * terms.k[i]));
}

/// Whether every value is finite. For a run-time size of a floating-point type, x - x is 0 for a
/// finite x and NaN otherwise: one pass without branches, four sums so that it vectorises (a lane
/// system's state has n·W values; rk4 on a run-time size of 6 takes 10% less time). A static size
/// keeps the plain loop, which the compiler unrolls (2% faster there).
template <class V> inline bool all_finite(const V& v) {
    using T = std::decay_t<decltype(v[0])>;
    const std::size_t n = size_of(v);
    if constexpr (std::is_floating_point_v<T> && !std::is_aggregate_v<V>) {
        T sum[4] = {T(0), T(0), T(0), T(0)};
        const std::size_t whole = n / 4 * 4;
        for (std::size_t i = 0; i < whole; i += 4)
            for (std::size_t k = 0; k < 4; ++k)
                sum[k] += v[i + k] - v[i + k];
        for (std::size_t i = whole; i < n; ++i)
            sum[0] += v[i] - v[i];
        return sum[0] + sum[1] + sum[2] + sum[3] == T(0);
    } else {
        using std::isfinite;
        bool ok = true;
        for (std::size_t i = 0; i < n; ++i)
            ok = ok && isfinite(v[i]);
        return ok;
    }
}

template <class To, class From> inline void assign(To& to, const From& from) {
    for (std::size_t i = 0; i < size_of(from); ++i)
        to[i] = from[i];
}

} // namespace rotgen::detail
