/// \file
/// rotgen runtime — the implicit midpoint rule, fixed step (symplectic, symmetric, order 2).
///
///   y1 = y0 + h f(t + h/2, (y0 + y1)/2)
/// Written for the midpoint z = (y0 + y1)/2, so that y1 = 2z − y0:
///   g(z) = z − y0 − (h/2) f(t + h/2, z) = 0.
/// Simplified Newton iteration (Hairer, Lubich & Wanner, Geometric Numerical Integration, VIII.6;
/// Hairer & Wanner II, IV.8): the iteration matrix M = I − (h/2) J, J = ∂f/∂y at the predictor,
/// is LU-factorised once per step (Eigen::PartialPivLU) and
///   Δz = −M⁻¹ g(z),  z ← z + Δz.
/// Predictor: z0 = y0 + (h/2) k, k the slope (y1 − y0)/h of the previous step (f(t0, y0) first).
/// Convergence test on the increment, in the weighted max-norm ‖Δ‖ = max_i |Δ_i| / (atol +
/// rtol·|z_i|) with atol = rtol = newton_tol (default 10·eps): converged when ‖Δ‖ <= 1, or when the
/// observed contraction θ = ‖Δ_k‖/‖Δ_{k−1}‖ < 1 predicts the remaining error θ/(1−θ)·‖Δ_k‖ <= 1, or
/// when the increments stall at the rounding level (‖Δ‖ <= 100 and θ >= 1). Iterating to rounding
/// level keeps the map symplectic to working precision, so the energy error stays bounded over long
/// runs. If the iteration diverges (θ >= 1 above the rounding level) or needs more than
/// max_newton_iter iterations, the Jacobian is re-evaluated at the current iterate and the
/// iteration restarted once; failing again, integrate() returns status::newton_failure at the last
/// good state.
///
/// Samples between grid points: cubic Hermite interpolation from y and f at the step ends (the
/// f at the end costs one evaluation in steps that hold samples). The trajectory itself does not
/// depend on the samples.
/// Stepper concept (stepper.hpp): order 2, no error estimate, Hermite dense output, Jacobian.
#pragma once

#include <Eigen/LU>

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "../derivatives.hpp"
#include "../stepper.hpp"

namespace rotgen {

template <class T, class S> class implicit_midpoint_stepper;

/// Options of the implicit midpoint rule: a fixed step and the Newton iteration's tolerance and
/// iteration limit.
template <class T> struct implicit_midpoint {
    /// The floating-point type of the run.
    using scalar = T;
    /// Marks a method the driver accepts (stepper.hpp).
    static constexpr bool is_rotgen_method = true;
    /// Fixed step: the options are `step` and `max_steps`; no error estimate.
    static constexpr bool adaptive = false;
    /// The stepper for a system of type S.
    template <class S> using stepper = implicit_midpoint_stepper<T, S>;

    T step = T(0);                     ///< step size h > 0
    std::size_t max_steps = 100000000; ///< step budget
    T newton_tol = T(0);               ///< 0: 10·eps(T), see above
    int max_newton_iter = 12;          ///< per attempt (two attempts per step)

    /// The method's name, as scene files and `rotgen simulate` spell it.
    std::string name() const { return "implicit_midpoint"; }
    /// An empty string when the options are valid, else the reason (one line).
    std::string check() const {
        using std::isfinite;
        if (!(step > T(0)) || !isfinite(step)) return "step must be finite and > 0";
        if (!(newton_tol >= T(0))) return "newton_tol must be >= 0";
        if (max_newton_iter < 1) return "max_newton_iter must be >= 1";
        return "";
    }
};

/// The implicit midpoint rule's working storage for one system type S (the stepper concept of
/// stepper.hpp): the Newton iteration on the midpoint equation with Eigen's LU.
template <class T, class S> class implicit_midpoint_stepper {
  public:
    /// The floating-point type of the run.
    using scalar = T;
    /// The system type S this stepper integrates.
    using system_type = S;
    /// The state vector of S.
    using vector = state_vector<T, S>;
    /// The N×N matrix of the Newton iteration (derivatives.hpp).
    using matrix = jacobian_matrix<T, S>;

    /// What attempt() returns.
    using outcome = step_outcome<T>;

    /// Order p of the step: local error O(h^(p+1)).
    static constexpr int order = 2;
    /// No error estimate: attempt() returns err = 0.
    static constexpr bool error_estimate = false;
    /// Samples inside a step come from the driver's cubic Hermite interpolation over
    /// hermite_ends().
    static constexpr dense_kind dense_output = dense_kind::hermite;
    /// Order of the interpolant (local error O(h^(dense_order+1))).
    static constexpr int dense_order = 3;
    /// Evaluates ∂f/∂y (system.jacobian, or finite differences when the system has none).
    static constexpr bool uses_jacobian = true;

    /// Storage for n state components, with the options of m.
    implicit_midpoint_stepper(const implicit_midpoint<T>& m, std::size_t n)
        : m_tol(m.newton_tol > T(0) ? m.newton_tol : T(10) * std::numeric_limits<T>::epsilon()),
          m_max_iter(m.max_newton_iter), m_y0(vector::Zero(n)), m_y1(m_y0), m_z(m_y0), m_fz(m_y0),
          m_g(m_y0), m_dz(m_y0), m_k(m_y0), m_f0(m_y0), m_f1(m_y0), m_jac(matrix::Zero(n, n)),
          m_iter(matrix::Identity(n, n)) {}

    /// f(t0, y0), after start() (for the initial step selection).
    const vector& f_start() const { return m_f0; }
    /// The state at t + h of the last attempt().
    const vector& y_new() const { return m_y1; }

    /// Begins a run at (t0, y0): evaluates f(t0, y0); false when it is not finite.
    bool start(const S& sys, T t0, const vector& y0, step_stats& stats) {
        detail::eval_rhs(sys, t0, y0, m_f1, stats);
        m_f1_valid = true;
        m_k = m_f1; // first predictor slope
        return m_f1.allFinite();
    }

    /// One step of size h from (t, y) into y_new(): the midpoint equation solved by Newton's
    /// method; code ok, non_finite or newton_failure, err 0 (no estimate).
    outcome attempt(const S& sys, T t, const vector& y, T h, step_stats& stats, bool) {
        m_y0 = y;
        m_h = h;
        m_t1 = t + h;
        m_f0_valid = m_f1_valid;
        if (m_f1_valid) m_f0.swap(m_f1); // f(t, y) known from the previous step's end
        m_f1_valid = false;
        const T tm = t + h / T(2);
        const T h2 = h / T(2);
        m_z = y + h2 * m_k; // predictor
        for (int pass = 0; pass < 2; ++pass) {
            if (!m_z.allFinite()) m_z = y;
            detail::eval_rhs(sys, tm, m_z, m_fz, stats);
            if (!m_fz.allFinite()) return {status::non_finite, T(0)};
            detail::eval_jacobian(sys, tm, m_z, m_fz, m_jac, stats);
            // M = I − (h/2) J
            m_iter = -h2 * m_jac;
            m_iter.diagonal().array() += T(1);
            m_lu.compute(m_iter);
            ++stats.factorisations;
            T dn_old = T(0);
            for (int it = 0; it < m_max_iter; ++it) {
                if (it > 0) detail::eval_rhs(sys, tm, m_z, m_fz, stats);
                m_g = m_z - y - h2 * m_fz; // g(z) = z − y0 − (h/2) f(t + h/2, z)
                m_dz = -m_lu.solve(m_g);
                if (!m_dz.allFinite()) break;
                m_z += m_dz;
                const T dn = weighted_norm(m_dz, m_z);
                if (dn <= T(1)) return finish(y, h);
                if (it > 0) {
                    const T theta = dn / dn_old;
                    if (theta < T(1) && theta / (T(1) - theta) * dn <= T(1)) return finish(y, h);
                    if (theta >= T(1)) {
                        if (dn <= T(100)) return finish(y, h); // stalled at the rounding level
                        break;                                 // diverging
                    }
                }
                dn_old = dn;
            }
        }
        return {status::newton_failure, T(0)};
    }

    /// The driver accepted the last attempt: prepares the next step and, when need_dense, the
    /// interpolant; false when f at the new state is not finite.
    bool accept(const S& sys, step_stats& stats, bool need_dense) {
        m_k = (m_y1 - m_y0) / m_h; // = f(t + h/2, z): slope of this step, next predictor
        if (need_dense) {
            if (!m_f0_valid) { // f(t, y0) is needed for the interpolant too
                detail::eval_rhs(sys, m_t1 - m_h, m_y0, m_f0, stats);
                m_f0_valid = true;
            }
            detail::eval_rhs(sys, m_t1, m_y1, m_f1, stats);
            m_f1_valid = true;
            return m_f1.allFinite();
        }
        return true;
    }

    /// The Hermite data of the last accepted step with samples: y0, f(t, y0), y1, f(t + h, y1).
    step_ends<T, vector> hermite_ends() const { return {m_h, m_y0, m_f0, m_y1, m_f1}; }

  private:
    /// max_i |d_i| / (tol + tol·|z_i|)
    T weighted_norm(const vector& d, const vector& z) const {
        return (d.array().abs() / (m_tol * (T(1) + z.array().abs()))).maxCoeff();
    }

    outcome finish(const vector& y, T /*h*/) {
        m_y1 = T(2) * m_z - y; // y1 = 2z − y0
        return {m_y1.allFinite() ? status::ok : status::non_finite, T(0)};
    }

    T m_tol;
    int m_max_iter;
    T m_h = T(0), m_t1 = T(0);
    bool m_f0_valid = false, m_f1_valid = false;
    vector m_y0, m_y1, m_z, m_fz, m_g, m_dz, m_k, m_f0, m_f1;
    matrix m_jac, m_iter;
    Eigen::PartialPivLU<Eigen::Matrix<T, state_dim<S>(), state_dim<S>()>> m_lu;
};

static_assert(check_method<implicit_midpoint<double>>());

} // namespace rotgen
