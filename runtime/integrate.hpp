// rotgen runtime — the common driver: integrate(system, method, t0, y, sample_times, observer).
//
//   t0            start time
//   y             in: state at t0 (state_vector<T, S>); out: state at result.t
//   sample_times  any container with size() and operator[] (std::vector<T>, Eigen vector …),
//                 non-decreasing in the direction of integration, all on the same side of t0;
//                 the last one is the end time (backward integration when it is before t0)
//   observer      callable observer(T t, const state_vector<T, S>& y), called once per sample,
//                 in order; samples equal to t0 get the initial state
//
// How samples between step boundaries are filled:
//   dopri5         4th-order continuous extension of Dormand–Prince (Shampine), free
//   dop853         7th-order continuous extension, 3 extra f evaluations in steps holding samples
//   rk4, implicit_midpoint, rosenbrock
//                  cubic Hermite interpolation from y and f at both ends of the step (local
//                  error O(h^4): consistent with RK4's and below the midpoint rule's accuracy;
//                  for RODAS4 it is one order below the step, as documented in rosenbrock.hpp).
// Fixed-step methods step on the grid t_k = t0 + k·h (never accumulated by addition) and shorten
// the last step to end exactly at the end time; when (t_end − t0)/h is within rounding of an
// integer, that integer number of steps is taken (no sliver step).
//
// Guards (status values, never exceptions): non-finite initial state or f(t0, y0) → non_finite;
// fixed-step methods stop with non_finite at the last finite state; adaptive methods reject a
// step with non-finite stage values and retry with h/4, ending with non_finite if the step then
// underflows; |h| < 16·eps·|t| → step_size_underflow; more than max_steps attempts → max_steps.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>

#include "combine.hpp"
#include "result.hpp"
#include "step_control.hpp"
#include "system.hpp"

namespace rotgen {

namespace detail {

template <class M, class = void> struct is_method : std::false_type {};
template <class M> struct is_method<M, std::enable_if_t<M::is_rotgen_method>> : std::true_type {};

// Cubic Hermite interpolation on a step [t, t + h] at t + θh from y and f at both ends:
//   y(θ) = (1+2θ)(1−θ)² y0 + θ(1−θ)² h f0 + θ²(3−2θ) y1 + θ²(θ−1) h f1
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

template <class T> std::string format_time(T t) {
    std::ostringstream os;
    os.precision(std::numeric_limits<T>::digits10 + 2);
    os << static_cast<long double>(t);
    return os.str();
}

// The messages of a stopped integration, out of line: they are built once per run at most, and
// keeping them out of the stepping loop keeps the loop small enough for the compiler to hold the
// state in registers.
template <class T> ROTGEN_COLD std::string underflow_message(bool nonfinite, T h, T t) {
    return (nonfinite ? std::string("non-finite values in the stages; ") : std::string()) +
           "step size " + format_time(h) + " underflows at t = " + format_time(t);
}
template <class T> ROTGEN_COLD std::string max_steps_message(std::size_t max_steps, T t) {
    return "max_steps = " + std::to_string(max_steps) + " reached at t = " + format_time(t);
}
template <class T> ROTGEN_COLD std::string newton_message(T t, T h) {
    return "Newton iteration did not converge in the step from t = " + format_time(t) +
           " with h = " + format_time(h);
}
template <class T> ROTGEN_COLD std::string nonfinite_message(const char* what, T t) {
    return what + format_time(t);
}

template <class T>
integration_result<T> fail(status code, std::string msg, T t, const step_stats& s) {
    integration_result<T> r;
    r.code = code;
    r.message = std::move(msg);
    r.t = t;
    r.stats = s;
    return r;
}

} // namespace detail

template <class M> inline constexpr bool is_method_v = detail::is_method<M>::value;

template <class S, class Method, class Times, class Observer,
          std::enable_if_t<is_method_v<Method>, int> = 0>
integration_result<typename Method::scalar>
integrate(const S& sys, const Method& method, detail::identity_t<typename Method::scalar> t0,
          state_vector<typename Method::scalar, S>& y, const Times& sample_times,
          Observer&& observer) {
    using T = typename Method::scalar;
    using vector = state_vector<T, S>;
    using std::abs;
    using std::isfinite;
    using std::max;
    using std::min;
    step_stats stats;
    const T eps = std::numeric_limits<T>::epsilon();

    // ---- validate the arguments ----
    const std::size_t n = system_size(sys);
    if (n == 0 || static_cast<std::size_t>(y.size()) != n)
        return detail::fail<T>(status::invalid_argument,
                               "state has " + std::to_string(y.size()) +
                                   " components, system expects " + std::to_string(n),
                               t0, stats);
    if (std::string why = method.check(); !why.empty())
        return detail::fail<T>(status::invalid_argument, method.name() + std::string(": ") + why,
                               t0, stats);
    const std::size_t ns = static_cast<std::size_t>(sample_times.size());
    if (ns == 0)
        return detail::fail<T>(status::invalid_argument, "no sample times given", t0, stats);
    if (!isfinite(t0))
        return detail::fail<T>(status::invalid_argument, "start time is not finite", t0, stats);
    const T t_end = T(sample_times[ns - 1]);
    const T dir = t_end >= t0 ? T(1) : T(-1);
    for (std::size_t i = 0; i < ns; ++i) {
        const T s = T(sample_times[i]);
        const T prev = i == 0 ? t0 : T(sample_times[i - 1]);
        if (!isfinite(s))
            return detail::fail<T>(status::invalid_argument,
                                   "sample time " + std::to_string(i) + " is not finite", t0,
                                   stats);
        if (dir * (s - prev) < T(0))
            return detail::fail<T>(status::invalid_argument,
                                   "sample times must be monotone in the direction of integration "
                                   "(sample " +
                                       std::to_string(i) + " = " + detail::format_time(s) + ")",
                                   t0, stats);
    }
    if (!y.allFinite())
        return detail::fail<T>(status::non_finite, "initial state is not finite", t0, stats);

    // ---- samples at t0 ----
    std::size_t idx = 0;
    while (idx < ns && T(sample_times[idx]) == t0) {
        observer(t0, static_cast<const vector&>(y));
        ++idx;
    }
    integration_result<T> res;
    res.t = t0;
    if (idx == ns) return res;

    typename Method::template stepper<S> st(method, n);
    if (!st.start(sys, t0, y, stats))
        return detail::fail<T>(status::non_finite,
                               "f(t0, y0) is not finite at t = " + detail::format_time(t0), t0,
                               stats);

    constexpr bool adaptive = Method::adaptive;
    const T span = abs(t_end - t0);
    bool controlled = false;
    T hmax = span;
    T hn = T(0);            // nominal step of the fixed-step mode
    std::size_t nsteps = 0; // grid of the fixed-step mode: t_k = t0 + dir·k·hn, t_nsteps = t_end
    if constexpr (adaptive) {
        controlled = method.fixed_step == T(0);
        if (method.hmax > T(0)) hmax = min(method.hmax, span);
        hn = method.fixed_step;
    } else {
        hn = method.step;
    }
    const std::size_t max_steps = method.max_steps;
    auto controller = detail::make_controller(method, st.order());
    T h = T(0);
    if constexpr (adaptive) {
        if (controlled)
            h = method.h0 > T(0)
                    ? dir * min(method.h0, hmax)
                    : detail::initial_step(sys, t0, y, st.f_start(), dir, hmax, method.atol,
                                           method.rtol, st.order(), stats);
    }
    if (!controlled) {
        using std::ceil;
        using std::round;
        const T q = span / hn;
        if (q >= T(max_steps) + T(2)) {
            nsteps = max_steps + 2; // the step budget runs out first
        } else {
            const T qr = round(q);
            nsteps = static_cast<std::size_t>(
                abs(q - qr) <= T(1000) * eps * max(q, T(1)) ? qr : ceil(q));
            nsteps = max<std::size_t>(nsteps, 1);
        }
    }

    // The current state lives in a local copy while stepping (registers, for small static sizes;
    // the caller's vector would be stored and reloaded on every step) and goes back to `y` at the end.
    vector y_now = y;
    vector ys = y; // scratch for dense output
    T t = t0;
    bool last_nonfinite = false;
    for (std::size_t k = 0;;) {
        bool last = false;
        T t_next;
        if (controlled) {
            h = dir * min(abs(h), hmax);
            if (dir * (t + T(1.01) * h - t_end) >= T(0)) {
                h = t_end - t;
                last = true;
            }
            t_next = last ? t_end : t + h;
        } else {
            last = k + 1 == nsteps;
            t_next = last ? t_end : t0 + dir * (T(static_cast<long long>(k + 1)) * hn);
            h = t_next - t;
        }
        if (!(abs(h) >= T(16) * eps * abs(t)) || h == T(0)) {
            res.code = last_nonfinite ? status::non_finite : status::step_size_underflow;
            res.message = detail::underflow_message(last_nonfinite, abs(h), t);
            break;
        }
        if (stats.steps >= max_steps) {
            res.code = status::max_steps;
            res.message = detail::max_steps_message(max_steps, t);
            break;
        }
        ++stats.steps;
        const bool need_dense = idx < ns && dir * (T(sample_times[idx]) - t_next) < T(0);
        const auto out = st.attempt(sys, t, y_now, h, stats, need_dense);
        if (out.code == status::newton_failure) {
            res.code = status::newton_failure;
            res.message = detail::newton_message(t, h);
            break;
        }
        if (out.code == status::non_finite) {
            if (!controlled) {
                res.code = status::non_finite;
                res.message =
                    detail::nonfinite_message("state became non-finite in the step from t = ", t);
                break;
            }
            ++stats.rejected;
            last_nonfinite = true;
            h = controller.rejected(h, std::numeric_limits<T>::infinity());
            continue;
        }
        if (controlled && !(out.err <= T(1))) {
            ++stats.rejected;
            last_nonfinite = false;
            h = controller.rejected(h, out.err);
            continue;
        }
        // ---- accepted ----
        ++stats.accepted;
        last_nonfinite = false;
        const bool f_ok = st.accept(sys, stats, need_dense);
        while (idx < ns && dir * (T(sample_times[idx]) - t_next) < T(0)) {
            st.dense((T(sample_times[idx]) - t) / h, ys);
            observer(T(sample_times[idx]), static_cast<const vector&>(ys));
            ++idx;
        }
        detail::assign(y_now, st.y_new());
        t = t_next;
        res.last_step = h;
        while (idx < ns && T(sample_times[idx]) == t) {
            observer(t, static_cast<const vector&>(y_now));
            ++idx;
        }
        if (last) break;
        if (!f_ok) {
            res.code = status::non_finite;
            res.message = detail::nonfinite_message("f(t, y) is not finite at t = ", t);
            break;
        }
        ++k;
        if (controlled) h = controller.accepted(h, out.err);
    }
    y = y_now;
    res.t = t;
    res.stats = stats;
    return res;
}

// Integrate to t_end without samples; y holds the state at result.t on return.
template <class S, class Method, std::enable_if_t<is_method_v<Method>, int> = 0>
integration_result<typename Method::scalar>
integrate(const S& sys, const Method& method, detail::identity_t<typename Method::scalar> t0,
          state_vector<typename Method::scalar, S>& y,
          detail::identity_t<typename Method::scalar> t_end) {
    using T = typename Method::scalar;
    const T times[1] = {t_end};
    struct one_sample {
        const T* p;
        std::size_t size() const { return 1; }
        T operator[](std::size_t) const { return *p; }
    };
    return integrate(sys, method, t0, y, one_sample{times}, [](T, const state_vector<T, S>&) {});
}

} // namespace rotgen
