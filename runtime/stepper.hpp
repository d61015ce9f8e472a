/// \file
/// rotgen runtime — the method and stepper concepts: what the driver (integrate/) asks of an
/// integration method, written down once. Every stepper in steppers/ states which parts it models
/// and checks itself with `static_assert(rotgen::check_stepper<...>())`.
///
/// Two types make up a method, as in Boost.Odeint's Stepper / ErrorStepper / ControlledStepper /
/// DenseOutputStepper, but with the roles split differently: the *method* is the user's value (the
/// options), the *stepper* the working storage the driver builds from it for one system type.
/// Odeint asks the user to pick a stepper category (and wraps steppers into controlled and dense
/// ones); rotgen's driver reads the stepper's declared properties instead and supplies what a
/// stepper lacks itself: step-size control (a PI controller) for any stepper with an error
/// estimate, cubic Hermite interpolation for any stepper without a continuous extension.
///
/// ---- Method M (rk4<T>, dopri5<T>, dop853<T>, implicit_midpoint<T>, rodas4<T>) ------------------
///   using scalar = T;                             the floating-point type of the run
///   static constexpr bool is_rotgen_method = true;
///   static constexpr bool adaptive;               true: M is an adaptive_options<T> (rtol, atol,
///                                                 h0, hmax, fixed_step, safety, facmin, facmax,
///                                                 beta, max_steps) and its stepper has an error
///                                                 estimate; false: M has `step` and `max_steps`
///   `template <class S> using stepper = ...;`     the stepper for system type S (below)
///   std::string name() const;                     "dop853", ...
///   std::string check() const;                    "" when the options are valid, else the reason
///
/// ---- Stepper St (for scalar T and system S; St = M::stepper<S>)
/// --------------------------------- Properties (compile-time constants, read by the driver and by
/// users choosing a method):
///   using scalar = T;  using system_type = S;
///   static constexpr int order;                   order p of the step: local error O(h^(p+1));
///                                                 the PI controller's exponent is 1/p and the
///                                                 initial step guess uses p
///   static constexpr bool error_estimate;         attempt() returns a weighted error norm err
///                                                 (step accepted when err <= 1); equals
///                                                 M::adaptive
///   static constexpr dense_kind dense_output;     continuous_extension: the stepper interpolates
///                                                 itself (dense()); hermite: the driver
///                                                 interpolates by cubic Hermite from
///                                                 hermite_ends()
///   static constexpr int dense_order;             order of the interpolant (local error
///                                                 O(h^(dense_order+1))); 3 for Hermite
///   static constexpr bool uses_jacobian;          evaluates ∂f/∂y (system.jacobian, or finite
///                                                 differences when S has none)
/// Step functions, called by the driver in this order:
///   St(const M& method, std::size_t n)            storage for n state components
///   bool start(const S&, T t0, const state_vector<T, S>& y0, step_stats&)
///                                                 evaluates f(t0, y0); false if it is not finite
///   const W& f_start() const                      f(t0, y0) after start (initial step selection)
///   then per step:
///   step_outcome<T> attempt(const S&, T t, const state_vector<T, S>& y, T h, step_stats&,
///                           bool need_dense)      one step of size h from (t, y) into y_new();
///                                                 code ok / non_finite / newton_failure, err as
///                                                 above (0 without an error estimate);
///                                                 need_dense: samples fall inside this step
///   bool accept(const S&, step_stats&, bool need_dense)
///                                                 the driver accepted the step: prepare the next
///                                                 one (FSAL) and, if need_dense, the interpolant;
///                                                 false if f at the new state is not finite
///   const W& y_new() const                        the state at t + h of the last attempt
///   and for sampling inside an accepted step (θ = (t_sample − t)/h ∈ [0, 1)):
///   void dense(T θ, state_vector<T, S>& out) const          if continuous_extension
///   step_ends<T, W> hermite_ends() const                    if hermite: h, y and f at both ends
/// Optional, for a stepper that chooses its own step (the Taylor method; M::chooses_step and
/// St::chooses_step true, M::adaptive false; M has rtol, atol, step, hmax, max_steps and
/// `template <class S> static constexpr bool supports`, false for a system it cannot integrate):
///   T choose_step(const S&, T t, const state_vector<T, S>& y, step_stats&)
///                                                 the step the tolerance allows from (t, y) (> 0;
///                                                 not > 0: the coefficients are not finite);
///                                                 attempt() then takes a step of at most that size
///                                                 and is never rejected
///                                                 (integrate/self_stepping.hpp)
/// W is any vector type with size() and operator[] (state_vector or the work vectors of
/// combine.hpp). A stepper never includes the driver; the driver never names a stepper.
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>

#include "result.hpp"
#include "system.hpp"

namespace rotgen {

/// How samples between step boundaries are produced (see above).
enum class dense_kind {
    continuous_extension, ///< the stepper's own interpolant, St::dense(θ, out)
    hermite               ///< the driver's cubic Hermite from St::hermite_ends()
};

/// Result of one attempted step.
template <class T> struct step_outcome {
    status code; ///< ok, non_finite (stage values or y_new not finite), newton_failure
    T err;       ///< weighted error norm (<= 1: acceptable); 0 for steppers without an estimate
};

/// What a Hermite stepper exposes after accept(…, true): the step size and y, f at both ends.
template <class T, class W> struct step_ends {
    T h;         ///< the step size
    const W& y0; ///< y at the start of the step
    const W& f0; ///< f at the start of the step
    const W& y1; ///< y at the end of the step
    const W& f1; ///< f at the end of the step
};

namespace detail {

/// Archetypes: the smallest systems (static and run-time size) a stepper must work with; the
/// concept checks instantiate steppers on them. Declarations only: never called.
struct archetype_system {
    static constexpr std::size_t state_size = 3;
    void rhs(double t, const double* y, double* dydt) const;
};
struct archetype_dynamic_system {
    std::size_t size() const;
    void rhs(double t, const double* y, double* dydt) const;
};

template <class M, class = void> struct is_method : std::false_type {};
template <class M> struct is_method<M, std::enable_if_t<M::is_rotgen_method>> : std::true_type {};

// ---- one detector per part of the stepper concept ----

template <class St, class = void> struct has_types : std::false_type {};
template <class St>
struct has_types<St, std::void_t<typename St::scalar, typename St::system_type>> : std::true_type {
};

template <class St, class = void> struct has_properties : std::false_type {};
template <class St>
struct has_properties<
    St, std::enable_if_t<std::is_same_v<std::remove_cv_t<decltype(St::order)>, int> &&
                         std::is_same_v<std::remove_cv_t<decltype(St::error_estimate)>, bool> &&
                         std::is_same_v<std::remove_cv_t<decltype(St::dense_output)>, dense_kind> &&
                         std::is_same_v<std::remove_cv_t<decltype(St::dense_order)>, int> &&
                         std::is_same_v<std::remove_cv_t<decltype(St::uses_jacobian)>, bool>>>
    : std::bool_constant<(St::order > 0) && (St::dense_order > 0)> {};

template <class St> using state_of = state_vector<typename St::scalar, typename St::system_type>;

template <class St, class = void> struct has_start : std::false_type {};
template <class St>
struct has_start<
    St,
    std::enable_if_t<std::is_same_v<
        decltype(std::declval<St&>().start(
            std::declval<const typename St::system_type&>(), std::declval<typename St::scalar>(),
            std::declval<const state_of<St>&>(), std::declval<step_stats&>())),
        bool>>> : std::true_type {};

template <class St, class = void> struct has_attempt : std::false_type {};
template <class St>
struct has_attempt<St,
                   std::enable_if_t<std::is_convertible_v<
                       decltype(std::declval<St&>().attempt(
                           std::declval<const typename St::system_type&>(),
                           std::declval<typename St::scalar>(), std::declval<const state_of<St>&>(),
                           std::declval<typename St::scalar>(), std::declval<step_stats&>(), true)),
                       step_outcome<typename St::scalar>>>> : std::true_type {};

template <class St, class = void> struct has_accept : std::false_type {};
template <class St>
struct has_accept<
    St, std::enable_if_t<std::is_same_v<decltype(std::declval<St&>().accept(
                                            std::declval<const typename St::system_type&>(),
                                            std::declval<step_stats&>(), true)),
                                        bool>>> : std::true_type {};

template <class St, class = void> struct has_states : std::false_type {};
template <class St>
struct has_states<St, std::void_t<decltype(std::declval<const St&>().y_new()[0]),
                                  decltype(std::declval<const St&>().f_start()[0])>>
    : std::true_type {};

template <class St, class = void> struct has_dense : std::false_type {};
template <class St>
struct has_dense<St, std::void_t<decltype(std::declval<const St&>().dense(
                         std::declval<typename St::scalar>(), std::declval<state_of<St>&>()))>>
    : std::true_type {};

template <class St, class = void> struct has_hermite_ends : std::false_type {};
template <class St>
struct has_hermite_ends<St, std::void_t<decltype(std::declval<const St&>().hermite_ends().y0[0])>>
    : std::true_type {};

template <class St, bool = has_properties<St>::value> struct has_interpolant : std::false_type {};
template <class St>
struct has_interpolant<St, true>
    : std::bool_constant<St::dense_output == dense_kind::continuous_extension
                             ? has_dense<St>::value
                             : has_hermite_ends<St>::value> {};

template <class St, bool = has_types<St>::value> struct is_stepper : std::false_type {};
template <class St>
struct is_stepper<St, true>
    : std::bool_constant<has_properties<St>::value && has_start<St>::value &&
                         has_attempt<St>::value && has_accept<St>::value && has_states<St>::value &&
                         has_interpolant<St>::value> {};

} // namespace detail

/// True when M is a method (option struct) the driver accepts.
template <class M> inline constexpr bool is_method_v = detail::is_method<M>::value;

/// True when St models the stepper concept above.
template <class St> inline constexpr bool is_stepper_v = detail::is_stepper<St>::value;

/// The concept check with one message per missing part; `static_assert(check_stepper<St>())`.
template <class St> constexpr bool check_stepper() {
    static_assert(detail::has_types<St>::value,
                  "a stepper declares `using scalar = T;` and `using system_type = S;`");
    if constexpr (detail::has_types<St>::value) {
        static_assert(detail::has_properties<St>::value,
                      "a stepper declares static constexpr int order (> 0), bool error_estimate, "
                      "dense_kind dense_output, int dense_order (> 0), bool uses_jacobian");
        static_assert(detail::has_start<St>::value,
                      "a stepper has bool start(const S&, T t0, const state_vector<T, S>&, "
                      "step_stats&)");
        static_assert(detail::has_attempt<St>::value,
                      "a stepper has step_outcome<T> attempt(const S&, T t, const "
                      "state_vector<T, S>&, T h, step_stats&, bool need_dense)");
        static_assert(detail::has_accept<St>::value,
                      "a stepper has bool accept(const S&, step_stats&, bool need_dense)");
        static_assert(detail::has_states<St>::value,
                      "a stepper has y_new() and f_start(), vectors indexed by operator[]");
        static_assert(detail::has_interpolant<St>::value,
                      "a stepper with dense_output == continuous_extension has dense(T theta, "
                      "state_vector<T, S>&) const; one with hermite has hermite_ends() const");
    }
    return is_stepper_v<St>;
}

/// The check of a method's stepper on the archetype systems (static and run-time size), and the
/// agreement of M::adaptive with the stepper's error estimate.
template <class M> constexpr bool check_method() {
    static_assert(is_method_v<M>, "a method declares static constexpr bool is_rotgen_method");
    using fixed = typename M::template stepper<detail::archetype_system>;
    using dynamic = typename M::template stepper<detail::archetype_dynamic_system>;
    static_assert(fixed::error_estimate == M::adaptive,
                  "M::adaptive must equal the stepper's error_estimate");
    return check_stepper<fixed>() && check_stepper<dynamic>();
}

} // namespace rotgen
