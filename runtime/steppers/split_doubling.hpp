/// \file
/// rotgen runtime — split2, split4, split6 under error control: a local error estimate by step
/// doubling (Richardson) and the driver's PI controller (integrate/adaptive.hpp).
///
/// Each attempted step of size h runs the composition Φ (steppers/splitting.hpp) once with h and
/// twice with h/2 from the same start. For a method of order p the two results differ by
///   Φ_{h/2}∘Φ_{h/2}(y) − Φ_h(y) = (2^p − 1) · C h^(p+1) + O(h^(p+2)),
/// where C h^(p+1)/2^p is the local error of the two half steps, so
///   err = ‖(Φ_{h/2}∘Φ_{h/2}(y) − Φ_h(y)) / (2^p − 1)‖   (error_norm, atol + rtol·|y|)
/// estimates the error of the propagated result, the two half steps (HNW I, §II.4, "Richardson
/// extrapolation"; not extrapolated, so each step stays a composition of exact flows). The cost is
/// 1.5 compositions per step of the propagated solution.
///
/// Why step doubling rather than an embedded pair made of the stages (Blanes, Casas & Thalhammer
/// 2019; Auzinger et al. 2017): those estimators are linear combinations of the stage values, which
/// here live on the unit quaternions and come from nonlinear exact flows, and they need
/// coefficients derived for each composition; the doubling estimate needs neither, is
/// asymptotically exact for every order, and compares two runs of the method itself, so an error
/// the method makes by aliasing a fast motion (steps far longer than the nutation period) shows as
/// a difference between h and h/2 unless both alias alike. The controller searches downward: a
/// rejected step is retried shorter (h · max(facmin, safety / err^(1/p))) until the estimate is
/// below 1, and an accepted step lets the next grow by at most facmax = 2, so a step is never
/// chosen by a jump over a stretch of step sizes whose error is not monotone in h. On the goal grid
/// (bench/results/split_control.md: spins 10 to 1e4, theta0 0.3 and 1.2, two bodies) every run's
/// error at t = 10 is within 10 rtol (or twice DOP853's at the same rtol) this way, with the
/// estimate held to 0.05 of the tolerance.
///
/// Scenes (calibrate(), step_control.hpp) hold the estimate to 0.05 · c_p · τ^(1/p) of sk instead
/// (c_p = calibrated_scale, τ = rtol): the propagated result is the one the estimate measures, so
/// a local error held to τ^((p+1)/p) makes a global error proportional to τ (error per unit step;
/// held to τ, the global error goes as τ^(p/(p+1)): 46x of spread in error ÷ rtol over 1e-5 …
/// 1e-10 for split2; bench/results/proportionality.md).
///
/// Adaptive steps give up exact symplecticity (HLW, Geometric Numerical Integration, ch. VIII): the
/// fixed-step mode (split_method, `step`) is the structure-preserving one.
/// Stepper concept (stepper.hpp): order 2/4/6, error estimate, continuous extension (the two half
/// steps of θh/2 from the step's start: equal to the step's result at θ = 1), no Jacobian.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "../step_control.hpp"
#include "splitting.hpp"

namespace rotgen {

template <class T, class S, int Order> class split_doubling_stepper;

/// Options: adaptive_options (rtol, atol, h0, hmax, fixed_step, safety, facmin, facmax, beta,
/// max_steps) with facmax 2 and the I controller; fixed_step > 0 runs the two half steps per step
/// without control.
template <class T, int Order> struct split_controlled : adaptive_options<T> {
    static_assert(Order == 2 || Order == 4 || Order == 6, "split methods of order 2, 4, 6");
    /// The floating-point type of the run.
    using scalar = T;
    /// Marks a method the driver accepts (stepper.hpp).
    static constexpr bool is_rotgen_method = true;
    /// Error-controlled: the options are adaptive_options and the stepper has an error estimate.
    static constexpr bool adaptive = true;
    /// Runs only on a split system (split_system.hpp).
    static constexpr bool needs_split_system = true;
    /// The stepper for a system of type S.
    template <class S> using stepper = split_doubling_stepper<T, S, Order>;

    /// calibrate()'s values for scenes (bench/proportionality: rtol means the error at the samples)
    static constexpr double calibrated_scale = Order == 2 ? 160.0 : Order == 4 ? 25.0 : 2.0;
    static constexpr double calibrated_power = 1.0 / Order; ///< see calibrated_scale

    split_controlled() {
        this->facmax = T(2);
        this->beta = T(0);
    }
    /// The defaults with the tolerances rtol, atol.
    split_controlled(T rtol, T atol) : split_controlled() {
        this->rtol = rtol;
        this->atol = atol;
    }
    /// The estimate is held to tolerance_scale · (atol + rtol |y|): local errors add up over the
    /// run, and this keeps the global error near rtol (bench/results/split_control.md).
    T tolerance_scale = T(0.05);
    /// A step turns the body (|ω| h) by at most max_turns · 2π: on longer steps the doubling
    /// estimate aliases with the spin and can miss the error a hundredfold (split2 at spin 1000,
    /// rtol 1e-4: 107 steps and 108 × rtol; bench/results/split_control.md). The bound enters the
    /// error as (|ω| h / (2π max_turns))^p, so the controller settles below it without rejecting.
    /// 0: no bound.
    T max_turns = T(5);

    /// The method's name, as scene files and `rotgen simulate` spell it.
    std::string name() const { return "split" + std::to_string(Order); }
    /// An empty string when the options are valid, else the reason (one line).
    std::string check() const {
        if (!(tolerance_scale > T(0) && tolerance_scale <= T(1)))
            return "tolerance_scale must lie in (0, 1]";
        if (!(this->calibration_scale > T(0)) || !(this->calibration_power >= T(0)))
            return "calibration_scale must be > 0 and calibration_power >= 0";
        if (!(max_turns >= T(0))) return "max_turns must be >= 0";
        return detail::check_adaptive_options<T>(*this);
    }
};

/// The working storage of split2/4/6 under error control for one split system type S (the
/// stepper concept of stepper.hpp; the estimate in the file's comment).
template <class T, class S, int Order> class split_doubling_stepper {
  public:
    /// The floating-point type of the run.
    using scalar = T;
    /// The system type S this stepper integrates.
    using system_type = S;
    /// The state vector of S.
    using vector = state_vector<T, S>;
    using flows = split_stepper<T, S, Order>; ///< the uncontrolled composition (splitting.hpp)
                                              ///< whose steps it takes

    /// Order p of the step: local error O(h^(p+1)).
    static constexpr int order = Order;
    /// attempt() returns a weighted error norm (step accepted when <= 1).
    static constexpr bool error_estimate = true;
    /// Samples inside a step come from the stepper's own interpolant, dense().
    static constexpr dense_kind dense_output = dense_kind::continuous_extension;
    /// Order of the interpolant (local error O(h^(dense_order+1))).
    static constexpr int dense_order = Order;
    /// Never evaluates ∂f/∂y.
    static constexpr bool uses_jacobian = false;

    /// Storage for n state components, with the tolerances of m times m.tolerance_scale.
    split_doubling_stepper(const split_controlled<T, Order>& m, std::size_t n)
        : m_atol(m.atol * factor(m)), m_rtol(m.rtol * factor(m)),
          m_max_angle(T(2) * T(3.14159265358979323846) * m.max_turns), m_layout(m.layout),
          m_y0(detail::make_work_vector<vector>(n)), m_y1(m_y0), m_full(m_y0), m_mid(m_y0),
          m_f(m_y0), m_inv(m_y0) {}

    /// f(t0, y0), after start() (for the initial step selection).
    const vector& f_start() const { return m_f; }
    /// The state at t + h of the last attempt().
    const vector& y_new() const { return m_y1; }

    /// Begins a run at (t0, y0): evaluates f(t0, y0); false when it is not finite.
    bool start(const S& sys, T t0, const vector& y0, step_stats& stats) {
        detail::eval_rhs(sys, t0, y0, m_f, stats);
        return detail::all_finite(m_f);
    }

    /// One step of size h from (t, y) into y_new(): the composition once with h and twice with h/2
    /// (the result), err the doubling estimate; code ok or non_finite.
    step_outcome<T> attempt(const S& sys, T t, const vector& y, T h, step_stats& stats,
                            bool need_dense) {
        flows::advance(sys, t, y, h, m_full, stats);
        flows::advance(sys, t, y, h / T(2), m_mid, stats);
        flows::advance(sys, t + h / T(2), m_mid, h / T(2), m_y1, stats);
        m_sys = &sys, m_t = t, m_h = h;
        if (need_dense) m_y0 = y;
        if (!detail::all_finite(m_y1) || !detail::all_finite(m_full))
            return {status::non_finite, T(0)};
        const T scale = T(1) / T((1 << Order) - 1);
        for (std::size_t i = 0; i < detail::size_of(m_full); ++i)
            m_full[i] = (m_y1[i] - m_full[i]) * scale;
        const T err = detail::error_norm(m_full, y, m_y1, m_atol, m_rtol, m_layout, m_inv);
        return {status::ok, std::max(err, turning(y, h))};
    }

    /// Nothing to prepare (samples are the method run from the step's start): always true.
    bool accept(const S&, step_stats&, bool) { return true; }

    /// The state at t + θh: two half steps of θh/2 from the step's start.
    void dense(T theta, vector& out) const {
        step_stats unused;
        vector mid = out;
        flows::advance(*m_sys, m_t, m_y0, theta * m_h / T(2), mid, unused);
        flows::advance(*m_sys, m_t + theta * m_h / T(2), mid, theta * m_h / T(2), out, unused);
    }

  private:
    /// (|ω| |h| / (2π max_turns))^p, ω = y[4..6] (a split system's state: q, then ω); 0 without
    /// the bound.
    T turning(const vector& y, T h) const {
        using std::abs;
        using std::sqrt;
        if (!(m_max_angle > T(0))) return T(0);
        const T w = sqrt(y[4] * y[4] + y[5] * y[5] + y[6] * y[6]);
        T r = T(1);
        for (int k = 0; k < Order; ++k)
            r *= abs(h) * w / m_max_angle;
        return r;
    }

    static T factor(const split_controlled<T, Order>& m) {
        return m.tolerance_scale *
               calibration_factor(m.calibration_scale, m.calibration_power, m.rtol, m.atol);
    }

    T m_atol, m_rtol, m_max_angle;
    error_layout m_layout;
    vector m_y0, m_y1, m_full, m_mid, m_f, m_inv;
    const S* m_sys = nullptr;
    T m_t = T(0), m_h = T(0);
};

/// split2 (Strang) under error control.
template <class T> using split2_controlled = split_controlled<T, 2>;
/// split4 (Suzuki) under error control.
template <class T> using split4_controlled = split_controlled<T, 4>;
/// split6 (Yoshida) under error control.
template <class T> using split6_controlled = split_controlled<T, 6>;

static_assert(check_method<split4_controlled<double>>());

} // namespace rotgen
