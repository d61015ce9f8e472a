/// \file
/// rotgen runtime — the loop of the methods that choose their own step (the Taylor method,
/// steppers/taylor.hpp): the stepper expands the solution at (t, y) and says how far the expansion
/// reaches within the tolerance (choose_step); the loop takes that step, never rejected.
///
///   each    h = min(choose_step(), hmax) (hmax: method.hmax if > 0, else |t_end − t0|); a step
///           that would end within 1% of h before t_end is stretched to end exactly there
///   non-finite coefficients or state: the run ends with status::non_finite
/// Guards: |h| < 16·eps·|t| → step_size_underflow; more than max_steps steps → max_steps.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>

#include "../combine.hpp"
#include "../result.hpp"
#include "../system.hpp"
#include "messages.hpp"
#include "step_end.hpp"

namespace rotgen::detail {

/// True when the method's stepper chooses its own step (Method::chooses_step).
template <class M, class = void> struct chooses_step : std::false_type {};
template <class M> struct chooses_step<M, std::enable_if_t<M::chooses_step>> : std::true_type {};

/// (hi, lo) + h as (hi', lo'), |lo'| <= ulp(hi')/2: Knuth's two-sum of hi + h, its error joined
/// to lo, renormalised (the time of a long run of many steps keeps the steps' exact sum).
template <class T> void add_compensated(T hi, T lo, T h, T& hi_out, T& lo_out) {
    const T s = hi + h;
    const T b = s - hi;
    const T e = ((hi - (s - b)) + (h - b)) + lo;
    hi_out = s + e;
    lo_out = e - (hi_out - s);
}

template <class S, class Method, class Sampler, class T>
ROTGEN_NOINLINE integration_result<T> run_self_stepping(const S& sys, const Method& method, T t0,
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
    integration_result<T> res;
    state_vector<T, S> y_now = y; // local copies while stepping: see fixed.hpp
    state_vector<T, S> ys = y;
    Sampler samples = sampler_in;
    T t = t0, t_lo = T(0); // t + t_lo: the sum of the steps taken, compensated (double-double)
    for (;;) {
        if (stats.steps >= method.max_steps) {
            res.code = status::max_steps;
            res.message = max_steps_message(method.max_steps, t);
            break;
        }
        const T reach = st.choose_step(sys, t, y_now, stats);
        if (!(reach > T(0))) {
            res.code = status::non_finite;
            res.message = nonfinite_message("the Taylor coefficients are not finite at t = ", t);
            break;
        }
        T h = dir * min(reach, hmax);
        const bool last = dir * (t + T(1.01) * h - t_end) >= T(0);
        if (last) h = (t_end - t) - t_lo; // the steps' exact sum reaches t_end
        T t_next = t_end, lo_next = T(0);
        if (!last) add_compensated(t, t_lo, h, t_next, lo_next);
        if (!(abs(h) >= T(16) * eps * abs(t)) || h == T(0)) {
            res.code = status::step_size_underflow;
            res.message = underflow_message(false, abs(h), t);
            break;
        }
        ++stats.steps;
        const bool need_dense = samples.before(t_next);
        if (st.attempt(sys, t, y_now, h, stats, need_dense || Sampler::has_events).code !=
            status::ok) {
            res.code = status::non_finite;
            res.message = nonfinite_message("state became non-finite in the step from t = ", t);
            break;
        }
        ++stats.accepted;
        if (!end_of_step(sys, st, stats, samples, need_dense, t, t_next, h, last, y_now, ys, res))
            break;
        t_lo = lo_next;
    }
    y = y_now;
    res.t = t;
    res.stats = stats;
    return res;
}

} // namespace rotgen::detail
