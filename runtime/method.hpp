/// \file
/// rotgen runtime — choosing a method at run time (for scene files and the `simulate` command).
///
///   any_method<T>                       std::variant of the six method option structs
///   make_method<T>(name, rtol, atol, step) -> std::optional<any_method<T>>
///       names: rk4, dopri5, dop853, implicit_midpoint (or midpoint), rodas4 (or rosenbrock),
///       taylor;
///       rk4 and implicit_midpoint take `step`; the adaptive methods take rtol/atol, and `step`
///       if > 0 switches them to fixed steps without error control; taylor takes rtol/atol
///       (and `step` > 0: fixed steps) and needs a system with Taylor coefficients.
///   integrate(system, any_method, t0, y, sample_times, observer)   dispatches with std::visit.
#pragma once

#include <optional>
#include <string_view>
#include <utility>
#include <variant>

#include "integrate/integrate.hpp"
#include "steppers/dop853.hpp"
#include "steppers/dopri5.hpp"
#include "steppers/implicit_midpoint.hpp"
#include "steppers/rk4.hpp"
#include "steppers/rosenbrock.hpp"
#include "steppers/taylor.hpp"

namespace rotgen {

/// A method chosen at run time: one of the six option structs.
template <class T>
using any_method =
    std::variant<rk4<T>, dopri5<T>, dop853<T>, implicit_midpoint<T>, rodas4<T>, taylor<T>>;

/// The method named `name` ("rk4", "implicit_midpoint" or "midpoint", "dopri5", "dop853",
/// "rodas4" or "rosenbrock", "taylor") with the tolerances rtol, atol (adaptive methods and taylor)
/// and the step (fixed-step methods; for the adaptive ones a fixed step when > 0, for taylor its
/// upper bound, 0: none); the other options keep their defaults. std::nullopt for an unknown name;
/// the values are not checked here (the method's check() does that).
template <class T>
std::optional<any_method<T>> make_method(std::string_view name, T rtol, T atol, T step) {
    auto adaptive = [&](auto m) {
        m.rtol = rtol;
        m.atol = atol;
        m.fixed_step = step;
        return any_method<T>(m);
    };
    if (name == "rk4") {
        rk4<T> m;
        m.step = step;
        return any_method<T>(m);
    }
    if (name == "implicit_midpoint" || name == "midpoint") {
        implicit_midpoint<T> m;
        m.step = step;
        return any_method<T>(m);
    }
    if (name == "dopri5") return adaptive(dopri5<T>());
    if (name == "dop853") return adaptive(dop853<T>());
    if (name == "rodas4" || name == "rosenbrock") return adaptive(rodas4<T>());
    if (name == "taylor") {
        taylor<T> m;
        m.rtol = rtol;
        m.atol = atol;
        m.step = step;
        return any_method<T>(m);
    }
    return std::nullopt;
}

/// integrate() (integrate/integrate.hpp) with the method held in `method`.
template <class S, class T, class Times, class Observer>
integration_result<T> integrate(const S& sys, const any_method<T>& method, detail::identity_t<T> t0,
                                state_vector<T, S>& y, const Times& sample_times,
                                Observer&& observer) {
    return std::visit(
        [&](const auto& m) { return integrate(sys, m, t0, y, sample_times, observer); }, method);
}

/// The same with events (integrate/events.hpp).
template <class S, class T, class Times, class Observer>
integration_result<T> integrate(const S& sys, const any_method<T>& method, detail::identity_t<T> t0,
                                state_vector<T, S>& y, const Times& sample_times,
                                Observer&& observer, event_set<T, state_vector<T, S>>& events) {
    return std::visit(
        [&](const auto& m) { return integrate(sys, m, t0, y, sample_times, observer, events); },
        method);
}

/// integrate() to the end time t_end, no samples but the end (integrate/integrate.hpp), with the
/// method held in `method`.
template <class S, class T>
integration_result<T> integrate(const S& sys, const any_method<T>& method, detail::identity_t<T> t0,
                                state_vector<T, S>& y, detail::identity_t<T> t_end) {
    return std::visit([&](const auto& m) { return integrate(sys, m, t0, y, t_end); }, method);
}

} // namespace rotgen
