// rotgen runtime — lanes: W members of an ensemble (the same equations, their own initial values
// and parameter values) advanced together, one right-hand side call computing all W (a SIMD batch
// kernel), by the ordinary steppers and driver.
//
// A lane system holds n components of W lanes, component-major: component c of lane l is
// y[c·W + l], so that a batch kernel loads component c of every lane with one vector load. Every
// operation of an explicit Runge–Kutta step except the error norm acts on each component alone,
// so the steppers run a lane system unchanged:
//   rk4 (fixed step)  each lane takes exactly the scalar run's steps on the same grid, with the
//                     same arithmetic: a lane equals the scalar run of its member up to the batch
//                     kernel's rounding (its vector sin, cos, ...);
//   dop853            one step size for all lanes: the error norm of each lane is DOP853's (over
//                     that lane's n components, dop853.hpp) and the step is accepted or rejected
//                     for all lanes together by the largest of them (lane_error_sums below), so
//                     every lane meets the tolerance; the initial step guess (HINIT) is the RMS
//                     over all lanes. Samples come from each lane's own dense output.
// A lane can be stopped (stop(l)): its derivatives are 0 from then on, so it stays where it was
// and adds nothing to the error. The system stops a lane itself when its f is not finite
// (failed(l)), so that one lane's blow-up does not end the others' run; the caller reruns such a
// lane on its own.
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

// Kernel: void(T t, const T* y, T* dydt) over all lanes (the layout above).
template <class T, class Kernel> class lane_system {
  public:
    static constexpr bool is_lane_system = true;

    lane_system(Kernel kernel, std::size_t components, std::size_t lanes)
        : m_kernel(std::move(kernel)), m_n(components), m_w(lanes), m_state(lanes, live) {}

    std::size_t size() const { return m_n * m_w; }
    std::size_t components() const { return m_n; }
    std::size_t lanes() const { return m_w; }

    void rhs(T t, const T* y, T* dydt) const {
        m_kernel(t, y, dydt);
        if (m_all_live) {
            // x - x is 0 for a finite x and NaN otherwise: one branch-free pass that vectorises
            T sum[4] = {T(0), T(0), T(0), T(0)};
            const std::size_t size = m_n * m_w, whole = size / 4 * 4;
            for (std::size_t i = 0; i < whole; i += 4)
                for (std::size_t k = 0; k < 4; ++k)
                    sum[k] += dydt[i + k] - dydt[i + k];
            for (std::size_t i = whole; i < size; ++i)
                sum[0] += dydt[i] - dydt[i];
            if (sum[0] + sum[1] + sum[2] + sum[3] == T(0)) return;
        }
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

    void stop(std::size_t lane) {
        if (m_state[lane] == live) m_state[lane] = stopped;
        m_all_live = false;
    }
    bool is_live(std::size_t lane) const { return m_state[lane] == live; }
    bool failed_lane(std::size_t lane) const { return m_state[lane] == failed; }

  private:
    enum state : unsigned char { live, stopped, failed };
    Kernel m_kernel;
    std::size_t m_n, m_w;
    mutable std::vector<unsigned char> m_state; // rhs marks failed lanes
    mutable bool m_all_live = true;             // no lane stopped or failed
};

namespace detail {

template <class S, class = void> struct is_lane_system : std::false_type {};
template <class S>
struct is_lane_system<S, std::enable_if_t<S::is_lane_system>> : std::true_type {};
template <class S> inline constexpr bool is_lane_system_v = is_lane_system<S>::value;

// Sums of squares of K error terms for an error norm: one set for a system, one per lane for a
// lane system (component i belongs to lane i mod W). largest(norm, n) is the norm of the one set,
// or the largest over the lanes with n/W components each.
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
