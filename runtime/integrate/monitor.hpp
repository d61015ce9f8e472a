/// \file
/// rotgen runtime — an invariant monitor: the drift of conserved quantities over the samples.
///
/// Given callables v_i(t, y) -> T (the energy, a conserved momentum, |q| of a quaternion, …), the
/// monitor is an observer (void) that evaluates each at every sample it sees and keeps
///   first(i)      v_i at the first sample (normally t0)
///   last(i)       v_i at the latest sample
///   max_drift(i)  max over the samples of |v_i(t) − v_i(t_first)|   (NaN once a value is NaN)
///   samples()     the number of samples seen
/// The values can also be fed directly (record(values)), e.g. when the caller computes them from a
/// state it has mapped itself. The monitor keeps its first values across runs (a run continued in
/// another chart or form); reset() starts over.
///
///   invariant_monitor<double, Eigen::VectorXd> monitor;
///   monitor.add([&](double t, const Eigen::VectorXd& y) { return sys.energy(t, y.data()); });
///   integrate(sys, method, t0, y, times, observe_all(std::ref(monitor), record));
///   double drift = monitor.max_drift(0);
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

namespace rotgen {

/// An observer that keeps, for each invariant v_i(t, y), its first and latest value and the
/// largest drift |v_i(t) − v_i(t_first)| over the samples (see the file's comment).
template <class T, class State> class invariant_monitor {
  public:
    using function = std::function<T(T, const State&)>; ///< the type of an invariant, v(t, y) -> T

    invariant_monitor() = default;
    /// A monitor of the given invariants.
    explicit invariant_monitor(std::vector<function> invariants) {
        for (auto& v : invariants)
            add(std::move(v));
    }

    /// Adds an invariant (before the first sample); returns its index.
    std::size_t add(function v) {
        m_functions.push_back(std::move(v));
        m_first.push_back(T(0));
        m_last.push_back(T(0));
        m_drift.push_back(T(0));
        return m_functions.size() - 1;
    }

    /// The observer: evaluates every invariant at (t, y).
    void operator()(T t, const State& y) {
        for (std::size_t i = 0; i < m_functions.size(); ++i)
            m_last[i] = m_functions[i](t, y);
        record_last();
    }

    /// Records the values v[0..size()-1] of one sample computed by the caller.
    template <class Values> void record(const Values& v) {
        for (std::size_t i = 0; i < m_first.size(); ++i)
            m_last[i] = T(v[i]);
        record_last();
    }

    /// Forgets the samples: the next sample is the first again.
    void reset() {
        m_samples = 0;
        for (std::size_t i = 0; i < m_first.size(); ++i)
            m_first[i] = m_last[i] = m_drift[i] = T(0);
    }

    /// The number of invariants.
    std::size_t size() const { return m_first.size(); }
    /// The number of samples seen since construction or reset().
    std::size_t samples() const { return m_samples; }
    /// v_i at the first sample.
    T first(std::size_t i) const { return m_first[i]; }
    /// v_i at the latest sample.
    T last(std::size_t i) const { return m_last[i]; }
    /// max over the samples of |v_i(t) − v_i(t_first)|; NaN once a value was NaN.
    T max_drift(std::size_t i) const { return m_drift[i]; }

  private:
    void record_last() {
        using std::abs;
        using std::isnan;
        for (std::size_t i = 0; i < m_first.size(); ++i) {
            if (m_samples == 0) m_first[i] = m_last[i];
            const T d = abs(m_last[i] - m_first[i]);
            if (!isnan(m_drift[i]) && (d > m_drift[i] || isnan(d))) m_drift[i] = d; // NaN sticks
        }
        ++m_samples;
    }

    std::vector<function> m_functions;
    std::vector<T> m_first, m_last, m_drift;
    std::size_t m_samples = 0;
};

} // namespace rotgen
