/// \file
/// rotgen runtime — the fixed-step loop (rk4, implicit_midpoint, and the adaptive methods with
/// `fixed_step > 0`, which then run without error control).
///
/// Steps lie on the grid t_k = t0 + dir·k·h (computed from k, never accumulated by addition); the
/// last step is shortened to end exactly at the end time. When (t_end − t0)/h is within rounding
/// of an integer, that integer number of steps is taken (no sliver step).
/// Every step is accepted; a non-finite state ends the run with status::non_finite at the last
/// finite state, a failed Newton iteration with status::newton_failure.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "../combine.hpp"
#include "../result.hpp"
#include "../system.hpp"
#include "messages.hpp"
#include "step_end.hpp"

namespace rotgen::detail {

/// The grid t_k = t0 + dir·k·h, k = 0..steps(), with t_steps() = t_end.
template <class T> class fixed_grid {
  public:
    fixed_grid(T t0, T t_end, T h, std::size_t max_steps)
        : m_t0(t0), m_t_end(t_end), m_h(h), m_dir(t_end >= t0 ? T(1) : T(-1)) {
        using std::abs;
        using std::ceil;
        using std::max;
        using std::round;
        const T eps = std::numeric_limits<T>::epsilon();
        const T q = abs(t_end - t0) / h;
        if (q >= T(max_steps) + T(2)) {
            m_steps = max_steps + 2; // the step budget runs out first
        } else {
            const T qr = round(q);
            m_steps = static_cast<std::size_t>(
                abs(q - qr) <= T(1000) * eps * max(q, T(1)) ? qr : ceil(q));
            m_steps = max<std::size_t>(m_steps, 1);
        }
    }

    std::size_t steps() const { return m_steps; }
    /// t_k; exactly t_end for k = steps()
    T time(std::size_t k) const {
        return k == m_steps ? m_t_end : m_t0 + m_dir * (T(static_cast<long long>(k)) * m_h);
    }

  private:
    T m_t0, m_t_end, m_h, m_dir;
    std::size_t m_steps = 1;
};

/// The fixed-step loop from (t0, y) with nominal step h; y holds the final state on return.
/// The stepper and the counters are locals of the loop's function (not references from the
/// caller): the compiler then knows that the stepper's stores do not alias the system's parameters
/// and keeps them, and the counters, in registers.
template <class S, class Method, class Sampler, class T>
ROTGEN_NOINLINE integration_result<T> run_fixed(const S& sys, const Method& method, T t0, T t_end,
                                                T h_nominal, state_vector<T, S>& y,
                                                const Sampler& sampler_in) {
    using std::abs;
    const T eps = std::numeric_limits<T>::epsilon();
    typename Method::template stepper<S> st(method, system_size(sys));
    step_stats stats;
    if (!st.start(sys, t0, y, stats)) return start_failure(t0, stats);
    const std::size_t max_steps = method.max_steps;
    const fixed_grid<T> grid(t0, t_end, h_nominal, max_steps);
    integration_result<T> res;
    // The current state lives in a local copy while stepping (registers, for small static sizes;
    // the caller's vector would be stored and reloaded on every step) and goes back to `y` at the
    // end.
    state_vector<T, S> y_now = y;
    state_vector<T, S> ys = y; // scratch: the state at a sample inside a step
    Sampler samples = sampler_in;
    T t = t0;
    for (std::size_t k = 0;; ++k) {
        const bool last = k + 1 == grid.steps();
        const T t_next = grid.time(k + 1);
        const T h = t_next - t;
        if (!(abs(h) >= T(16) * eps * abs(t)) || h == T(0)) {
            res.code = status::step_size_underflow;
            res.message = underflow_message(false, abs(h), t);
            break;
        }
        if (stats.steps >= max_steps) {
            res.code = status::max_steps;
            res.message = max_steps_message(max_steps, t);
            break;
        }
        ++stats.steps;
        const bool need_dense = samples.before(t_next);
        // with events the stages are kept in every step: whether the interpolant is needed is known
        // only from g at the step's end (event_step.hpp)
        const auto out = st.attempt(sys, t, y_now, h, stats, need_dense || Sampler::has_events);
        if (out.code == status::newton_failure) {
            res.code = status::newton_failure;
            res.message = newton_message(t, h);
            break;
        }
        if (out.code == status::non_finite) {
            res.code = status::non_finite;
            res.message = nonfinite_message("state became non-finite in the step from t = ", t);
            break;
        }
        ++stats.accepted;
        if (!end_of_step(sys, st, stats, samples, need_dense, t, t_next, h, last, y_now, ys, res))
            break;
    }
    y = y_now;
    res.t = t;
    res.stats = stats;
    return res;
}

} // namespace rotgen::detail
