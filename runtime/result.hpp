/// \file
/// rotgen runtime — outcome of an integration: status, message, final time, step statistics.
///
/// Expected failures (a step size that underflows, a Newton iteration that does not converge,
/// the step budget running out, a state that stops being finite, bad arguments) are values of
/// `status`, never exceptions and never aborts (house style: Odeint's `success`/`fail`).
#pragma once

#include <cstddef>
#include <string>

namespace rotgen {

/// How an integration ended (integration_result::code).
enum class status {
    ok,                  ///< every requested sample was produced, the end time was reached
    step_size_underflow, ///< |h| fell below 16·eps·|t| (adaptive methods), e.g. near a blow-up
    newton_failure,      ///< the implicit solve (implicit midpoint) did not converge
    max_steps,           ///< the step budget (`max_steps`) was used up before the end time
    non_finite,          ///< NaN/Inf in the state or its derivative; stopped at the last good state
    invalid_argument, ///< bad options or sample times (non-positive tolerance, unsorted times, …)
    stopped_by_observer, ///< the observer returned false at the sample t (integrate/observer.hpp)
    stopped_by_event     ///< a terminal event occurred at t (integrate/events.hpp)
};

/// The enumerator's name as a string ("ok", "max_steps", …), for messages and files.
inline const char* status_name(status s) {
    switch (s) {
    case status::ok:
        return "ok";
    case status::step_size_underflow:
        return "step_size_underflow";
    case status::newton_failure:
        return "newton_failure";
    case status::max_steps:
        return "max_steps";
    case status::non_finite:
        return "non_finite";
    case status::invalid_argument:
        return "invalid_argument";
    case status::stopped_by_observer:
        return "stopped_by_observer";
    case status::stopped_by_event:
        return "stopped_by_event";
    }
    return "unknown";
}

/// Work counters, common to every method.
struct step_stats {
    std::size_t steps = 0;    ///< attempted steps (accepted + rejected)
    std::size_t accepted = 0; ///< steps whose result became the new state
    std::size_t rejected =
        0; ///< steps thrown away by the error control (or for non-finite stage values)
    std::size_t rhs_evals =
        0; ///< calls of system.rhs (including finite-difference Jacobians and ∂f/∂t)
    std::size_t jac_evals = 0;      ///< Jacobian evaluations (analytic or by finite differences)
    std::size_t factorisations = 0; ///< LU factorisations of an iteration matrix
};

/// Result of `integrate`. On return the caller's state vector holds the state at `t`:
/// the end time when `code == status::ok`, the state delivered at the sample `t` when
/// `code == status::stopped_by_observer`, the state at the event when `code ==
/// status::stopped_by_event`, otherwise the last good (accepted, finite) state.
template <class T> struct integration_result {
    status code = status::ok; ///< how the run ended
    std::string message;      ///< one line, empty when ok
    T t = T(0);               ///< time of the state left in the caller's vector
    T last_step = T(0);       ///< size of the last accepted step (signed)
    step_stats stats;         ///< work counters of the run

    /// True when the run reached its end time (code == status::ok).
    bool ok() const { return code == status::ok; }
};

} // namespace rotgen
