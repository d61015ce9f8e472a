/// \file
/// rotgen runtime — the controlled loop of the adaptive methods (dopri5, dop853, rodas4 with
/// `fixed_step == 0`): error-controlled steps with the PI controller of step_control.hpp.
///
///   h0      method.h0 if > 0, else the HINIT guess (step_control.hpp, initial_step)
///   each    |h| <= hmax (method.hmax if > 0, else |t_end − t0|); a step that would end within
///           1% of h before t_end is stretched to end exactly there (no sliver step)
///   h       taken as (t + h) − t, the step the clock takes: t + h rounds, and a state advanced by
///   h
///           while the clock advanced by another amount drifts from its time by the sum of the
///           roundings (exact by Sterbenz's lemma once |h| <= |t|). The drift was the error of
///           runs of many steps through fast motion: DOPRI5 on a top spinning at 1000 rad/s takes
///           680,721 steps to t = 10 at rtol 1e-10 and erred 5.58 rtol with the drift, 0.0147 rtol
///           (the reference's floor) without it (bench/results/proportionality.md). The Taylor
///           loop sums its steps compensated instead (self_stepping.hpp).
///   err <= 1  accepted, h ← controller.accepted(h, err)
///   err > 1   rejected, h ← controller.rejected(h, err)
///   err is the stepper's estimate, under the error per unit step with its share held at a floor
///           where the estimate shows rounding (step_control.hpp, share_floor)
///   non-finite stage values: rejected, h ← h/4; the run ends with status::non_finite if the step
///           then underflows
/// Guards: |h| < 16·eps·|t| → step_size_underflow; more than max_steps attempts → max_steps.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "../combine.hpp"
#include "../result.hpp"
#include "../step_control.hpp"
#include "../system.hpp"
#include "messages.hpp"
#include "step_end.hpp"

namespace rotgen::detail {

/// The controlled loop from (t0, y); y holds the final state on return. The stepper and the
/// counters are locals here (see fixed.hpp).
template <class S, class Method, class Sampler, class T>
ROTGEN_NOINLINE integration_result<T> run_adaptive(const S& sys, const Method& method, T t0,
                                                   T t_end, state_vector<T, S>& y,
                                                   const Sampler& sampler_in) {
    using std::abs;
    using std::min;
    using St = typename Method::template stepper<S>;
    St st(method, system_size(sys));
    step_stats stats;
    if (!st.start(sys, t0, y, stats)) return start_failure(t0, stats);
    const T eps = std::numeric_limits<T>::epsilon();
    const T dir = t_end >= t0 ? T(1) : T(-1);
    const T span = abs(t_end - t0);
    const T hmax = method.hmax > T(0) ? min(method.hmax, span) : span;
    const std::size_t max_steps = method.max_steps;
    pi_controller<T> controller(method, St::order);
    share_floor<T> floor(per_unit_step<St>::value ? method.layout : error_layout{}); // step_control
    T h = method.h0 > T(0) ? dir * min(method.h0, hmax)
                           : initial_step(sys, t0, y, st.f_start(), dir, hmax, method.atol,
                                          method.rtol, St::order, stats, method.layout);
    integration_result<T> res;
    state_vector<T, S> y_now = y; // local copies while stepping: see fixed.hpp
    state_vector<T, S> ys = y;
    Sampler samples = sampler_in;
    T t = t0;
    bool last_nonfinite = false;
    for (;;) {
        h = dir * min(abs(h), hmax);
        const bool last = dir * (t + T(1.01) * h - t_end) >= T(0);
        if (last) h = t_end - t;
        const T t_next = last ? t_end : t + h;
        h = t_next - t; // the step the state takes is the one the clock takes (above)
        if (!(abs(h) >= T(16) * eps * abs(t)) || h == T(0)) {
            res.code = last_nonfinite ? status::non_finite : status::step_size_underflow;
            res.message = underflow_message(last_nonfinite, abs(h), t);
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
        last_nonfinite = out.code == status::non_finite;
        const T err = floor.held(h, out.err);
        const bool rejected = last_nonfinite || !(err <= T(1));
        floor.attempted(h, err, rejected);
        if (rejected) {
            ++stats.rejected;
            h = controller.rejected(h, last_nonfinite ? std::numeric_limits<T>::infinity() : err);
            continue;
        }
        ++stats.accepted;
        if (!end_of_step(sys, st, stats, samples, need_dense, t, t_next, h, last, y_now, ys, res))
            break;
        h = controller.accepted(h, err);
    }
    y = y_now;
    res.t = t;
    res.stats = stats;
    return res;
}

} // namespace rotgen::detail
