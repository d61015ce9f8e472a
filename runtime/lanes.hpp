/// \file
/// rotgen runtime — lanes: W members of an ensemble (the same equations, their own initial values
/// and parameter values) advanced together, one right-hand side call computing all W (a SIMD batch
/// kernel), by the ordinary steppers and driver.
///
/// A lane system holds n components of W lanes, component-major: component c of lane l is
/// y[c·W + l], so that a batch kernel loads component c of every lane with one vector load. Every
/// operation of an explicit Runge–Kutta step except the error norm acts on each component alone,
/// so the steppers run a lane system unchanged:
///   rk4 (fixed step)  each lane takes exactly the scalar run's steps on the same grid, with the
///                     same arithmetic: a lane equals the scalar run of its member up to the batch
///                     kernel's rounding (its vector sin, cos, ...);
///   dop853            one step size for all lanes: the error norm of each lane is DOP853's (over
///                     that lane's n components, dop853.hpp) and the step is accepted or rejected
///                     for all lanes together by the largest of them (lane_error_sums below), so
///                     every lane meets the tolerance; the initial step guess (HINIT) is the RMS
///                     over all lanes. Samples come from each lane's own dense output;
///   taylor            one order and one step for all lanes, the smallest of the lanes'
///                     Jorba–Zou steps (lane_taylor_system below, steppers/taylor_lanes.hpp).
/// A lane can be stopped (stop(l)): its derivatives are 0 from then on, so it stays where it was
/// and adds nothing to the error. The system stops a lane itself when its f is not finite
/// (failed(l)), so that one lane's blow-up does not end the others' run; the caller reruns such a
/// lane on its own.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "combine.hpp"

namespace rotgen {

/// A system of W lanes of n components each, component-major (y[c·W + l]), from a batch kernel
/// over all lanes (see the file's comment).
/// Kernel: void(T t, const T* y, T* dydt) over all lanes (the layout above).
template <class T, class Kernel> class lane_system {
  public:
    static constexpr bool is_lane_system =
        true; ///< marks a lane system (the steppers' lane-aware error norms)

    /// n = components per lane, W = lanes; every lane starts live.
    lane_system(Kernel kernel, std::size_t components, std::size_t lanes)
        : m_kernel(std::move(kernel)), m_n(components), m_w(lanes), m_state(lanes, live) {}

    /// n·W, the length of the state vector.
    std::size_t size() const { return m_n * m_w; }
    /// n, the components of one lane.
    std::size_t components() const { return m_n; }
    /// W, the number of lanes.
    std::size_t lanes() const { return m_w; }

    /// f over all lanes by the kernel; a lane whose f is not finite is marked failed, and a lane
    /// that is stopped or failed gets dydt = 0 (it stays where it is).
    void rhs(T t, const T* y, T* dydt) const {
        m_kernel(t, y, dydt);
        if (m_all_live && all_finite(dydt, m_n * m_w)) return;
        for (std::size_t l = 0; l < m_w; ++l) {
            bool finite = m_state[l] == live;
            for (std::size_t c = 0; c < m_n && finite; ++c) {
                using std::isfinite;
                finite = isfinite(dydt[c * m_w + l]);
            }
            if (finite) continue;
            if (m_state[l] == live) m_state[l] = failed;
            m_all_live = false;
            for (std::size_t c = 0; c < m_n; ++c)
                dydt[c * m_w + l] = T(0);
        }
    }

    /// Stops lane l: its derivatives are 0 from now on (a lane that already ended keeps its state).
    void stop(std::size_t lane) { set(lane, stopped); }
    /// Its values are not finite (a Taylor expansion's, lane_taylor_system): as for f above.
    void fail(std::size_t lane) const { set(lane, failed); }
    /// True while lane l is neither stopped nor failed.
    bool is_live(std::size_t lane) const { return m_state[lane] == live; }
    /// True while no lane is stopped or failed (the fast path).
    bool all_live() const { return m_all_live; }
    /// True when lane l was stopped because its f (or Taylor coefficients) were not finite.
    bool failed_lane(std::size_t lane) const { return m_state[lane] == failed; }

    /// Whether v[0..size) are all finite: x - x is 0 for a finite x and NaN otherwise, one
    /// branch-free pass that vectorises.
    static bool all_finite(const T* v, std::size_t size) {
        T sum[4] = {T(0), T(0), T(0), T(0)};
        const std::size_t whole = size / 4 * 4;
        for (std::size_t i = 0; i < whole; i += 4)
            for (std::size_t k = 0; k < 4; ++k)
                sum[k] += v[i + k] - v[i + k];
        for (std::size_t i = whole; i < size; ++i)
            sum[0] += v[i] - v[i];
        return sum[0] + sum[1] + sum[2] + sum[3] == T(0);
    }

  private:
    enum state : unsigned char { live, stopped, failed };
    void set(std::size_t lane, state s) const {
        if (m_state[lane] == live) m_state[lane] = s;
        m_all_live = false;
    }
    Kernel m_kernel;
    std::size_t m_n, m_w;
    mutable std::vector<unsigned char> m_state; ///< rhs marks failed lanes
    mutable bool m_all_live = true;             ///< no lane stopped or failed
};

/// A lane system that also gives its lanes' Taylor coefficients (steppers/taylor_lanes.hpp):
/// taylor(t, c, order) runs Taylor(t, c, order) over all lanes, coefficient k of component i of
/// lane l at c[(i (order + 1) + k) W + l] (component i's order-0 values set by the caller), then
/// holds the lanes that are not live (their coefficients beyond order 0 become 0) and stops a lane
/// whose coefficients are not finite (failed(), as for f). Taylor may return a bool, whether every
/// coefficient it wrote is finite: a batch kernel knows it for an addition a batch, where the pass
/// over the coefficients that finds it otherwise took 3-6% of a heavy-top Taylor sweep in lanes.
template <class T, class Kernel, class Taylor>
class lane_taylor_system : public lane_system<T, Kernel> {
  public:
    /// A lane system from the batch kernel and the batch Taylor function over W lanes of n
    /// components.
    lane_taylor_system(Kernel kernel, Taylor taylor, std::size_t components, std::size_t lanes)
        : lane_system<T, Kernel>(std::move(kernel), components, lanes),
          m_taylor(std::move(taylor)) {}

    /// The number of Taylor series per lane (its n components).
    std::size_t taylor_series() const { return this->components(); }

    /// The Taylor coefficients of all lanes up to order (layout in the class comment); lanes that
    /// are not live are held (coefficients beyond order 0 set to 0), a lane with non-finite
    /// coefficients fails.
    void taylor(T t, T* c, int order) const {
        const std::size_t n = this->components(), w = this->lanes();
        const std::size_t stride = static_cast<std::size_t>(order + 1) * w;
        if constexpr (std::is_same_v<decltype(m_taylor(t, c, order)), bool>) {
            if (m_taylor(t, c, order) && this->all_live()) return;
        } else {
            m_taylor(t, c, order);
            if (this->all_live() && this->all_finite(c, n * stride)) return;
        }
        for (std::size_t l = 0; l < w; ++l) {
            bool finite = this->is_live(l);
            for (std::size_t j = 0; j < n * stride && finite; j += w) {
                using std::isfinite;
                finite = isfinite(c[j + l]);
            }
            if (finite) continue;
            this->fail(l);
            for (std::size_t i = 0; i < n; ++i)
                for (std::size_t k = 1; k <= static_cast<std::size_t>(order); ++k)
                    c[i * stride + k * w + l] = T(0);
        }
    }

  private:
    Taylor m_taylor;
};

namespace detail {

template <class S, class = void> struct is_lane_system : std::false_type {};
template <class S>
struct is_lane_system<S, std::enable_if_t<S::is_lane_system>> : std::true_type {};
template <class S> inline constexpr bool is_lane_system_v = is_lane_system<S>::value;

/// Sums of squares of K error terms for an error norm: one set for a system, one per lane for a
/// lane system (component i belongs to lane i mod W). largest(norm, n) is the norm of the one set,
/// or the largest over the lanes with n/W components each.
/// The lanes of a system: sys.lanes() for a lane system, else 1.
template <class S> std::size_t lanes_of(const S& sys) {
    if constexpr (is_lane_system_v<S>)
        return sys.lanes();
    else
        return (void)sys, std::size_t(1);
}

template <class T, class S, std::size_t K, bool = is_lane_system_v<S>> class lane_error_sums {
  public:
    explicit lane_error_sums(const S&) {}
    ROTGEN_ALWAYS_INLINE void add(std::size_t, std::size_t k, T r) { m_sum[k] += r * r; }
    template <class Norm> T largest(const Norm& norm, std::size_t n) const {
        return norm(m_sum, n);
    }

  private:
    std::array<T, K> m_sum{};
};

template <class T, class S, std::size_t K> class lane_error_sums<T, S, K, true> {
  public:
    explicit lane_error_sums(const S& sys) : m_w(sys.lanes()), m_sum(m_w) {}
    void add(std::size_t i, std::size_t k, T r) { m_sum[i % m_w][k] += r * r; }
    template <class Norm> T largest(const Norm& norm, std::size_t n) const {
        T worst = T(0);
        for (const auto& s : m_sum) {
            const T e = norm(s, n / m_w);
            if (!(e <= worst)) worst = e; // a NaN wins
        }
        return worst;
    }

  private:
    std::size_t m_w;
    std::vector<std::array<T, K>> m_sum;
};

} // namespace detail
} // namespace rotgen
