/// \file
/// rotgen runtime — what the fixed-step and the controlled loop both do after an accepted step
/// [t, t_next] of size h: let the stepper prepare the next step (and the interpolant), deliver the
/// samples inside the step and at its end, move the state forward.
#pragma once

#include "../combine.hpp"
#include "../result.hpp"
#include "event_step.hpp"
#include "messages.hpp"

namespace rotgen::detail {

/// Returns true when the loop goes on. False when the run ends here, with `res` set: the last
/// step; the observer asked to stop (status::stopped_by_observer, `t` and `y_now` at that
/// sample); f at the new state not finite (status::non_finite).
template <class S, class St, class Sampler, class T, class V>
ROTGEN_ALWAYS_INLINE bool end_of_step(const S& sys, St& st, step_stats& stats, Sampler& samples,
                                      bool need_dense, T& t, T t_next, T h, bool last, V& y_now,
                                      V& ys, integration_result<T>& res) {
    bool f_ok = true;
    res.last_step = h;
    if constexpr (Sampler::has_events) {
        if (!step_events(sys, st, stats, samples, need_dense, f_ok, t, t_next, h, y_now, ys, res))
            return false;
    } else {
        f_ok = st.accept(sys, stats, need_dense);
    }
    if (need_dense && !samples.deliver_inside(st, t, h, t_next, ys)) {
        y_now = ys;
        t = samples.stop_time();
        res.code = status::stopped_by_observer;
        res.message = stopped_message(t);
        return false;
    }
    assign(y_now, st.y_new());
    t = t_next;
    if (!samples.deliver_at(t, y_now)) {
        res.code = status::stopped_by_observer;
        res.message = stopped_message(t);
        return false;
    }
    if (last) return false;
    if (!f_ok) {
        res.code = status::non_finite;
        res.message = nonfinite_message("f(t, y) is not finite at t = ", t);
        return false;
    }
    return true;
}

} // namespace rotgen::detail
