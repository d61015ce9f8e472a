/// \file
/// rotgen runtime — the driver: integrate(system, method, t0, y, sample_times, observer).
///
///   t0            start time
///   y             in: state at t0 (state_vector<T, S>); out: state at result.t
///   sample_times  any container with size() and operator[] (std::vector<T>, Eigen vector …),
///                 non-decreasing in the direction of integration, all on the same side of t0;
///                 the last one is the end time (backward integration when it is before t0)
///   observer      callable observer(T t, const state_vector<T, S>& y), called once per sample,
///                 in order; samples equal to t0 get the initial state. It returns void, or bool
///                 to stop the run after a sample (false; see observer.hpp)
///
/// The parts: the stepper concept in ../stepper.hpp; fixed.hpp, the fixed-step loop on the grid
/// t_k = t0 + k·h; adaptive.hpp, the controlled loop; sampling.hpp, the samples between step
/// boundaries (the stepper's continuous extension or cubic Hermite); self_stepping.hpp, the loop
/// of a stepper that chooses its own step (Taylor); observer.hpp, observers that stop a run and
/// their combination; monitor.hpp and chart_switch.hpp, two ready-made observers; events.hpp and
/// event_step.hpp, zeros of event functions located on the dense output.
///
/// Guards (status values, never exceptions): invalid arguments → invalid_argument; non-finite
/// initial state or f(t0, y0) → non_finite; the loops' own guards are listed in fixed.hpp and
/// adaptive.hpp; an observer returning false → stopped_by_observer.
#pragma once

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include "../result.hpp"
#include "../stepper.hpp"
#include "../system.hpp"
#include "adaptive.hpp"
#include "event_step.hpp"
#include "events.hpp"
#include "fixed.hpp"
#include "messages.hpp"
#include "observer.hpp"
#include "sampling.hpp"
#include "self_stepping.hpp"

namespace rotgen {

namespace detail {

/// The validation of integrate()'s arguments: a failed result, or nothing when they are valid.
template <class T, class S, class Method, class Times>
std::optional<integration_result<T>> check_arguments(const S& sys, const Method& method, T t0,
                                                     const state_vector<T, S>& y,
                                                     const Times& sample_times) {
    using std::isfinite;
    const step_stats none;
    const std::size_t n = system_size(sys);
    if (n == 0 || static_cast<std::size_t>(y.size()) != n)
        return fail<T>(status::invalid_argument,
                       "state has " + std::to_string(y.size()) + " components, system expects " +
                           std::to_string(n),
                       t0, none);
    if (std::string why = method.check(); !why.empty())
        return fail<T>(status::invalid_argument, method.name() + std::string(": ") + why, t0, none);
    const std::size_t ns = static_cast<std::size_t>(sample_times.size());
    if (ns == 0) return fail<T>(status::invalid_argument, "no sample times given", t0, none);
    if (!isfinite(t0))
        return fail<T>(status::invalid_argument, "start time is not finite", t0, none);
    const T dir = T(sample_times[ns - 1]) >= t0 ? T(1) : T(-1);
    for (std::size_t i = 0; i < ns; ++i) {
        const T s = T(sample_times[i]);
        const T prev = i == 0 ? t0 : T(sample_times[i - 1]);
        if (!isfinite(s))
            return fail<T>(status::invalid_argument,
                           "sample time " + std::to_string(i) + " is not finite", t0, none);
        if (dir * (s - prev) < T(0))
            return fail<T>(status::invalid_argument,
                           "sample times must be monotone in the direction of integration "
                           "(sample " +
                               std::to_string(i) + " = " + format_time(s) + ")",
                           t0, none);
    }
    if (!y.allFinite()) return fail<T>(status::non_finite, "initial state is not finite", t0, none);
    return std::nullopt;
}

} // namespace detail

namespace detail {

/// The loop the method asks for, from (t0, y) with the samples (and events) still to deliver.
template <class S, class Method, class Sampler, class T>
integration_result<T> run_loop(const S& sys, const Method& method, T t0, T t_end,
                               state_vector<T, S>& y, const Sampler& samples) {
    if constexpr (chooses_step<Method>::value) {
        if constexpr (!Method::template supports<S>) {
            return fail<T>(status::invalid_argument,
                           method.name() + ": the system gives no Taylor coefficients "
                                           "(emit them with --outputs taylor)",
                           t0, step_stats{});
        } else {
            if (method.step == T(0)) return run_self_stepping(sys, method, t0, t_end, y, samples);
            return run_fixed(sys, method, t0, t_end, method.step, y, samples);
        }
    } else if constexpr (Method::adaptive) {
        if (method.fixed_step == T(0)) return run_adaptive(sys, method, t0, t_end, y, samples);
        return run_fixed(sys, method, t0, t_end, method.fixed_step, y, samples);
    } else {
        return run_fixed(sys, method, t0, t_end, method.step, y, samples);
    }
}

/// integrate() after its arguments were checked; `events` is null or an event_set.
template <class S, class Method, class Times, class Observer, class Events>
integration_result<typename Method::scalar>
integrate_checked(const S& sys, const Method& method, typename Method::scalar t0,
                  state_vector<typename Method::scalar, S>& y, const Times& sample_times,
                  Observer& observer, Events* events) {
    using T = typename Method::scalar;
    /// The state vector of S.
    using vector = state_vector<T, S>;
    const T t_end = T(sample_times[static_cast<std::size_t>(sample_times.size()) - 1]);
    const T dir = t_end >= t0 ? T(1) : T(-1);
    sampler<T, Times, Observer> samples(sample_times, dir, observer);
    integration_result<T> res;
    res.t = t0;
    if (!samples.deliver_at(t0, static_cast<const vector&>(y))) {
        res.code = status::stopped_by_observer;
        res.message = stopped_message(t0);
        return res;
    }
    if (samples.done()) return res;
    if constexpr (std::is_same_v<Events, std::nullptr_t>) {
        return run_loop(sys, method, t0, t_end, y, samples);
    } else {
        events->begin(t0, static_cast<const vector&>(y), t_end);
        return run_loop(sys, method, t0, t_end, y, event_sampler(samples, *events));
    }
}

} // namespace detail

/// Integrates dy/dt = f(t, y) of `sys` with `method` from t0 through the sample times, calling
/// the observer at each sample (the file's comment has the details).
/// \param sys the system (system.hpp): rhs, and optionally jacobian
/// \param method the method's options (rk4<T>, dopri5<T>, dop853<T>, implicit_midpoint<T>,
///        rodas4<T>, taylor<T>, split methods; stepper.hpp)
/// \param t0 the start time
/// \param y in: the state at t0; out: the state at result.t (the end time when the run is ok)
/// \param sample_times non-decreasing in the direction of integration; the last one is the end
///        time (before t0: a backward run)
/// \param observer called as observer(t, y) once per sample, in order; returning false stops the
///        run (status::stopped_by_observer)
/// \return the status, a one-line message when not ok, the time of the state in y, the last step
/// and the work counters; failures are statuses, never exceptions.
template <class S, class Method, class Times, class Observer,
          std::enable_if_t<is_method_v<Method>, int> = 0>
integration_result<typename Method::scalar>
integrate(const S& sys, const Method& method, detail::identity_t<typename Method::scalar> t0,
          state_vector<typename Method::scalar, S>& y, const Times& sample_times,
          Observer&& observer) {
    using T = typename Method::scalar;
    if (auto failed = detail::check_arguments<T>(sys, method, t0, y, sample_times)) return *failed;
    std::nullptr_t no_events = nullptr;
    return detail::integrate_checked(sys, method, t0, y, sample_times, observer, &no_events);
}

/// The same, watching events (events.hpp): zeros of each event's g(t, y) located on the dense
/// output and recorded in `events` (hits()); a terminal event ends the run with
/// status::stopped_by_event at its time.
template <class S, class Method, class Times, class Observer,
          std::enable_if_t<is_method_v<Method>, int> = 0>
integration_result<typename Method::scalar>
integrate(const S& sys, const Method& method, detail::identity_t<typename Method::scalar> t0,
          state_vector<typename Method::scalar, S>& y, const Times& sample_times,
          Observer&& observer,
          event_set<typename Method::scalar, state_vector<typename Method::scalar, S>>& events) {
    using T = typename Method::scalar;
    if (auto failed = detail::check_arguments<T>(sys, method, t0, y, sample_times)) return *failed;
    return detail::integrate_checked(sys, method, t0, y, sample_times, observer, &events);
}

/// Integrate to t_end without samples; y holds the state at result.t on return.
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
