/// \file
/// rotgen runtime — the classic 4th-order Runge–Kutta method, fixed step.
///
///   k1 = f(t, y)
///   k2 = f(t + h/2, y + h/2 k1)
///   k3 = f(t + h/2, y + h/2 k2)
///   k4 = f(t + h,   y + h k3)
///   y1 = y + h/6 (k1 + 2 k2 + 2 k3 + k4)                     (global error O(h^4))
///
/// Steps lie on the grid t0 + k·h; the last step is shortened to end exactly at the end time
/// (see integrate/fixed.hpp). Samples between grid points are filled by the driver's cubic Hermite
/// interpolation from y and f at both ends of the step (local error O(h^4), so the samples keep
/// order 4); f at the step end is the next step's k1, so the interpolation costs no extra
/// evaluations.
/// Stepper concept (stepper.hpp): order 4, no error estimate, Hermite dense output, no Jacobian.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>

#include "../combine.hpp"
#include "../derivatives.hpp"
#include "../stepper.hpp"

namespace rotgen {

template <class T, class S> class rk4_stepper;

/// Options of the classic RK4: a fixed step and a step budget.
template <class T> struct rk4 {
    /// The floating-point type of the run.
    using scalar = T;
    /// Marks a method the driver accepts (stepper.hpp).
    static constexpr bool is_rotgen_method = true;
    /// Fixed step: the options are `step` and `max_steps`; no error estimate.
    static constexpr bool adaptive = false;
    /// The stepper for a system of type S.
    template <class S> using stepper = rk4_stepper<T, S>;

    T step = T(0);                     ///< step size h > 0
    std::size_t max_steps = 100000000; ///< step budget

    /// The method's name, as scene files and `rotgen simulate` spell it.
    std::string name() const { return "rk4"; }
    /// An empty string when the options are valid, else the reason (one line).
    std::string check() const {
        using std::isfinite;
        return step > T(0) && isfinite(step) ? "" : "step must be finite and > 0";
    }
};

/// RK4's working storage for one system type S (the stepper concept of stepper.hpp).
template <class T, class S> class rk4_stepper {
  public:
    /// The floating-point type of the run.
    using scalar = T;
    /// The system type S this stepper integrates.
    using system_type = S;
    /// The state vector of S.
    using vector = state_vector<T, S>;
    using work = detail::work_vector<T, S>; ///< see combine.hpp
    /// What attempt() returns.
    using outcome = step_outcome<T>;

    /// Order p of the step: local error O(h^(p+1)).
    static constexpr int order = 4;
    /// No error estimate: attempt() returns err = 0.
    static constexpr bool error_estimate = false;
    /// Samples inside a step come from the driver's cubic Hermite interpolation over
    /// hermite_ends().
    static constexpr dense_kind dense_output = dense_kind::hermite;
    /// Order of the interpolant (local error O(h^(dense_order+1))).
    static constexpr int dense_order = 3;
    /// Never evaluates ∂f/∂y.
    static constexpr bool uses_jacobian = false;

    /// Storage for n state components (the options hold nothing the stepper needs).
    rk4_stepper(const rk4<T>&, std::size_t n)
        : m_y0(detail::make_work_vector<work>(n)), m_y1(m_y0), m_k1(m_y0),
          m_f1(m_y0), m_stages{m_y0, m_y0, m_y0, m_y0, m_y0, m_y0} {}

    /// f(t0, y0), after start() (for the initial step selection).
    const work& f_start() const { return m_f1; }
    /// The state at t + h of the last attempt().
    const work& y_new() const { return m_y1; }

    /// Begins a run at (t0, y0): evaluates f(t0, y0); false when it is not finite.
    bool start(const S& sys, T t0, const vector& y0, step_stats& stats) {
        work y = m_y0;
        detail::assign(y, y0);
        detail::eval_rhs(sys, t0, y, m_f1, stats); // becomes k1 of the first step
        m_f1_valid = true;
        return detail::all_finite(m_f1);
    }

    /// One step; y0 and k1 are kept for the Hermite interpolant only when the step holds samples.
    /// The stages are locals for a static size (registers), the stepper's own for a run-time size
    /// (no allocation per step; see combine.hpp).
    ROTGEN_ALWAYS_INLINE outcome attempt(const S& sys, T t, const vector& y, T h, step_stats& stats,
                                         bool need_dense) {
        if constexpr (static_state_size<S>() > 0) {
            stages local;
            return steps(sys, t, y, h, stats, need_dense, local);
        } else {
            return steps(sys, t, y, h, stats, need_dense, m_stages);
        }
    }

    /// The driver accepted the last attempt: prepares the next step and, when need_dense, the
    /// interpolant; false when f at the new state is not finite.
    ROTGEN_ALWAYS_INLINE bool accept(const S& sys, step_stats& stats, bool need_dense) {
        if (need_dense) { // f(t + h, y1) for the Hermite interpolant; reused as the next k1
            detail::eval_rhs(sys, m_t1, m_y1, m_f1, stats);
            m_f1_valid = true;
            return detail::all_finite(m_f1);
        }
        return true;
    }

    /// The Hermite data of the last accepted step with samples: y0, k1 = f(t, y0), y1, f(t + h,
    /// y1).
    step_ends<T, work> hermite_ends() const { return {m_h, m_y0, m_k1, m_y1, m_f1}; }

  private:
    struct stages {
        work y0, k1, k2, k3, k4, arg;
    };

    ROTGEN_ALWAYS_INLINE outcome steps(const S& sys, T t, const vector& y, T h, step_stats& stats,
                                       bool need_dense, stages& s) {
        using detail::make_term;
        using detail::stage;
        detail::assign(s.y0, y);
        m_h = h;
        const T h2 = h / T(2);
        if (m_f1_valid)
            s.k1 = m_f1; // f at the end of the previous step = f(t, y)
        else
            detail::eval_rhs(sys, t, s.y0, s.k1, stats);
        m_f1_valid = false;
        stage(s.arg, s.y0, h, make_term<T>(0.5L, s.k1));
        detail::eval_rhs(sys, t + h2, s.arg, s.k2, stats);
        stage(s.arg, s.y0, h, make_term<T>(0.5L, s.k2));
        detail::eval_rhs(sys, t + h2, s.arg, s.k3, stats);
        stage(s.arg, s.y0, h, make_term<T>(1.0L, s.k3));
        detail::eval_rhs(sys, t + h, s.arg, s.k4, stats);
        const T h6 = h / T(6);
        for (std::size_t i = 0; i < detail::size_of(s.y0); ++i)
            m_y1[i] = s.y0[i] + h6 * (s.k1[i] + T(2) * s.k2[i] + T(2) * s.k3[i] + s.k4[i]);
        if (need_dense) {
            m_y0 = s.y0;
            m_k1 = s.k1;
        }
        m_t1 = t + h;
        return {detail::all_finite(m_y1) ? status::ok : status::non_finite, T(0)};
    }

    T m_h = T(0), m_t1 = T(0);
    bool m_f1_valid = false;
    work m_y0, m_y1, m_k1, m_f1;
    stages m_stages; ///< a run-time size's stages (unused for a static size)
};

static_assert(check_method<rk4<double>>());

} // namespace rotgen
