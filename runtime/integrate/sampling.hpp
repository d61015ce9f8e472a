/// \file
/// rotgen runtime — samples: delivering the requested sample times to the observer, at step
/// boundaries (the state itself) and inside steps (the stepper's interpolant).
///
/// How samples between step boundaries are filled (St::dense_output, stepper.hpp):
///   dopri5         4th-order continuous extension of Dormand–Prince (Shampine), free
///   dop853         7th-order continuous extension, 3 extra f evaluations in steps holding samples
///   rk4, implicit_midpoint, rodas4
///                  cubic Hermite interpolation from y and f at both ends of the step (local
///                  error O(h^4): consistent with RK4's and below the midpoint rule's accuracy;
///                  for RODAS4 it is one order below the step, as documented in rosenbrock.hpp).
#pragma once

#include <cstddef>

#include "../combine.hpp"
#include "../stepper.hpp"
#include "observer.hpp"

namespace rotgen::detail {

/// Cubic Hermite interpolation on a step [t, t + h] at t + θh from y and f at both ends:
///   y(θ) = (1+2θ)(1−θ)² y0 + θ(1−θ)² h f0 + θ²(3−2θ) y1 + θ²(θ−1) h f1
template <class T, class V, class Out>
void hermite(T theta, T h, const V& y0, const V& f0, const V& y1, const V& f1, Out& out) {
    const T one_m = T(1) - theta;
    const T h00 = (T(1) + T(2) * theta) * one_m * one_m;
    const T h10 = theta * one_m * one_m * h;
    const T h01 = theta * theta * (T(3) - T(2) * theta);
    const T h11 = theta * theta * (theta - T(1)) * h;
    for (std::size_t i = 0; i < size_of(y0); ++i)
        out[static_cast<Eigen::Index>(i)] = h00 * y0[i] + h10 * f0[i] + h01 * y1[i] + h11 * f1[i];
}

/// The state at t + θh inside the last accepted step: the stepper's own continuous extension, or
/// cubic Hermite from the data it exposes.
template <class St, class T, class V> void interpolate(const St& st, T theta, V& out) {
    if constexpr (St::dense_output == dense_kind::continuous_extension) {
        st.dense(theta, out);
    } else {
        const auto e = st.hermite_ends();
        hermite(theta, e.h, e.y0, e.f0, e.y1, e.f1, out);
    }
}

/// The sample times still to deliver and the observer to deliver them to. `Times`: any container
/// with size() and operator[], validated by integrate() (monotone in the direction dir = ±1).
/// When the observer asks to stop, stop_time() is that sample's time. The loops keep a local copy
/// (a few scalars and two references: registers) and the scratch vector for interpolated states
/// apart, so that the compiler can keep both out of memory.
template <class T, class Times, class Observer> class sampler {
  public:
    static constexpr bool has_events = false; ///< event_step.hpp's event_sampler: true

    sampler(const Times& times, T dir, Observer& observer)
        : m_times(times), m_n(static_cast<std::size_t>(times.size())), m_dir(dir),
          m_observer(observer) {}

    bool done() const { return m_next == m_n; }
    /// A sample lies strictly before t (in the direction of integration): inside a step ending at
    /// t.
    bool before(T t) const { return m_next < m_n && m_dir * (next_time() - t) < T(0); }
    T stop_time() const { return m_stop_time; }

    /// Samples at exactly t, given the state y there; false when the observer asked to stop.
    template <class V> ROTGEN_ALWAYS_INLINE bool deliver_at(T t, const V& y) {
        while (m_next < m_n && next_time() == t) {
            ++m_next;
            if (!notify(m_observer, t, y)) return stop(t);
        }
        return true;
    }

    /// Samples inside the accepted step [t, t + h) of `st` (ending at t_next), interpolated into
    /// ys; false when the observer asked to stop (ys then holds the state at stop_time()).
    template <class St, class V>
    ROTGEN_ALWAYS_INLINE bool deliver_inside(const St& st, T t, T h, T t_next, V& ys) {
        while (before(t_next)) {
            const T ts = next_time();
            interpolate(st, (ts - t) / h, ys);
            ++m_next;
            if (!notify(m_observer, ts, static_cast<const V&>(ys))) return stop(ts);
        }
        return true;
    }

  private:
    T next_time() const { return T(m_times[m_next]); }
    bool stop(T t) {
        m_stop_time = t;
        return false;
    }

    const Times& m_times;
    std::size_t m_n;
    std::size_t m_next = 0;
    T m_dir;
    Observer& m_observer;
    T m_stop_time = T(0);
};

} // namespace rotgen::detail
