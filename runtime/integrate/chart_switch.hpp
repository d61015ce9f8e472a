/// \file
/// rotgen runtime — leaving the Euler-angle chart near gimbal lock: a predicate observer.
///
/// The z-x-z Euler angles (φ, θ, ψ) are singular where sin θ = 0 (θ = 0 or π: φ and ψ turn about
/// the same axis, and the Euler-angle forms divide by sin θ). chart_switch watches θ, the state
/// component at `theta_index`, and asks the run to stop (returns false, observer.hpp) at the first
/// sample, after the first one it sees, where
///   |sin θ| < threshold,
/// unless that sample is the end time `t_end` (nothing left to integrate). The run then ends with
/// status::stopped_by_observer at that sample, from where the caller continues in another chart
/// (`rotgen simulate` switches to the body form there: ω = J(q) q̇, (5.30)).
/// The first sample is exempt: a run started near the singularity is the caller's decision.
///
///   chart_switch<double> leave(1, 1e-3, t_end);             // theta = y[1]
///   auto r = integrate(sys, method, t0, y, times, observe_all(record, std::ref(leave)));
///   if (r.code == status::stopped_by_observer && leave.triggered()) { /* switch at r.t */ }
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

namespace rotgen {

/// A predicate observer that stops a run at the first sample (after the first) where
/// |sin θ| < threshold, θ the z-x-z nutation angle (see the file's comment).
template <class T> class chart_switch {
  public:
    /// Watches y[theta_index] (θ in radians); stops where |sin θ| < threshold, except at t_end
    /// (NaN: no end time is exempt).
    chart_switch(std::size_t theta_index, T threshold,
                 T t_end = std::numeric_limits<T>::quiet_NaN())
        : m_index(theta_index), m_threshold(threshold), m_t_end(t_end) {}

    /// The observer: false (stop) when the chart should be left at this sample.
    template <class State> bool operator()(T t, const State& y) {
        using std::abs;
        using std::sin;
        const bool first = m_samples++ == 0;
        m_sin_theta = abs(sin(T(y[static_cast<decltype(y.size())>(m_index)])));
        if (first || t == m_t_end || !(m_sin_theta < m_threshold)) return true;
        m_triggered = true;
        m_time = t;
        return false;
    }

    /// True when it stopped a run (at time()).
    bool triggered() const { return m_triggered; }
    T time() const { return m_time; } ///< the sample where it triggered (valid when triggered())
    T sin_theta() const { return m_sin_theta; } ///< |sin θ| at the latest sample
    /// The number of samples seen.
    std::size_t samples() const { return m_samples; }

  private:
    std::size_t m_index;
    T m_threshold, m_t_end;
    std::size_t m_samples = 0;
    bool m_triggered = false;
    T m_time = T(0), m_sin_theta = T(1);
};

} // namespace rotgen
