/// \file
/// rotgen runtime — the messages of a stopped integration and the result of a failed one.
///
/// They are out of line (ROTGEN_COLD): built once per run at most, and keeping them out of the
/// stepping loop keeps the loop small enough for the compiler to hold the state in registers.
#pragma once

#include <cstddef>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "../combine.hpp"
#include "../result.hpp"

namespace rotgen::detail {

template <class T> std::string format_time(T t) {
    std::ostringstream os;
    os.precision(std::numeric_limits<T>::digits10 + 2);
    os << static_cast<long double>(t);
    return os.str();
}

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
template <class T> ROTGEN_COLD std::string stopped_message(T t) {
    return "stopped by the observer at the sample t = " + format_time(t);
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

/// f(t0, y0) not finite: the stepper's start() failed.
template <class T> ROTGEN_COLD integration_result<T> start_failure(T t0, const step_stats& s) {
    return fail<T>(status::non_finite, "f(t0, y0) is not finite at t = " + format_time(t0), t0, s);
}

} // namespace rotgen::detail
