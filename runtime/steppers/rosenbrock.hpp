/// \file
/// rotgen runtime — RODAS4: a stiffly accurate, L-stable Rosenbrock method of order 4(3).
///
/// Method (Hairer & Wanner, Solving ODEs II, §IV.7, and the code RODAS; 6 stages, γ = 1/4),
/// in the transformed variables that avoid matrix-vector products (HW II, (7.25)):
///   (1/(hγ) I − J) K_i = f(t + α_i h, y0 + Σ_{j<i} a_ij K_j) + Σ_{j<i} (c_ij / h) K_j + h γ_i f_t
///   y1 = y0 + Σ m_j K_j,   err_vec = K_6   (embedded order 3)
/// with J = ∂f/∂y(t, y0) and f_t = ∂f/∂t(t, y0). The method is stiffly accurate (m_j = a_6j for
/// j < 6, m_6 = 1): y1 is the last stage value plus K_6, so R(∞) = 0 (L-stable).
/// J is the system's analytic Jacobian if it has one, else forward differences (which makes it a
/// W-method of lower order: give an analytic Jacobian). f_t is a central difference in t (two
/// evaluations of f per Jacobian, error O(eps^(2/3))), skipped when `autonomous` is set.
/// J and f_t are evaluated once per accepted state and reused after a rejection; the matrix is
/// factorised (Eigen::PartialPivLU) once per attempt. Per attempt: 5 evaluations of f; per
/// accepted step f(t + h, y1) (the next step's first stage and the Hermite end slope), plus 2 for
/// f_t unless autonomous, plus n for a finite-difference Jacobian.
/// Step control: err = RMS_i err_vec_i/(atol + rtol·max(|y0_i|, |y1_i|)) = O(h^4): controller
/// exponent 1/4 (q = 4), defaults safety 0.9, facmin 0.2, facmax 6, beta 0 as in RODAS.
/// Dense output: cubic Hermite from y and f at the step ends (local error O(h^4), one order below
/// the step's O(h^5); RODAS's own 3rd-order stage-based extension is not implemented).
/// The coefficients are those of Hairer & Wanner's RODAS (subroutine RODAS4 of rodas.f, as also
/// used by KPP's Rodas4); tests check order 4 on a non-autonomous nonlinear problem and R(−∞) = 0.
/// Stepper concept (stepper.hpp): order 4, error estimate, Hermite dense output, Jacobian.
#pragma once

#include <Eigen/LU>

#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include "../derivatives.hpp"
#include "../step_control.hpp"
#include "../stepper.hpp"

namespace rotgen {

/// The coefficients of RODAS4 (Hairer & Wanner's RODAS, in long double; the file's comment).
struct rodas4_tableau {
    static constexpr int stages = 6;            ///< the number of stages
    static constexpr long double gamma = 0.25L; ///< γ = γ_ii, the diagonal of the method
    /// α_i (stage times) and γ_i = Σ_j γ_ij (multipliers of h f_t)
    static constexpr long double alpha[6] = {0.0L, 0.386L, 0.21L, 0.63L, 1.0L, 1.0L};
    /// γ_i = Σ_j γ_ij
    static constexpr long double gamma_i[6] = {0.25L, -0.1043L, 0.1035L, -0.3620000000000023e-01L,
                                               0.0L,  0.0L};
    /// a_ij, strictly lower triangular, row-major (i = 2..6)
    static constexpr long double a[6][5] = {
        {0, 0, 0, 0, 0},
        {0.1544000000000000e+01L, 0, 0, 0, 0},
        {0.9466785280815826L, 0.2557011698983284L, 0, 0, 0},
        {0.3314825187068521e+01L, 0.2896124015972201e+01L, 0.9986419139977817L, 0, 0},
        {0.1221224509226641e+01L, 0.6019134481288629e+01L, 0.1253708332932087e+02L,
         -0.6878860361058950L, 0},
        {0.1221224509226641e+01L, 0.6019134481288629e+01L, 0.1253708332932087e+02L,
         -0.6878860361058950L, 1.0L}};
    /// c_ij, strictly lower triangular, row-major (i = 2..6)
    static constexpr long double c[6][5] = {
        {0, 0, 0, 0, 0},
        {-0.5668800000000000e+01L, 0, 0, 0, 0},
        {-0.2430093356833875e+01L, -0.2063599157091915L, 0, 0, 0},
        {-0.1073529058151375L, -0.9594562251023355e+01L, -0.2047028614809616e+02L, 0, 0},
        {0.7496443313967647e+01L, -0.1024680431464352e+02L, -0.3399990352819905e+02L,
         0.1170890893206160e+02L, 0},
        {0.8083246795921522e+01L, -0.7981132988064893e+01L, -0.3152159432874371e+02L,
         0.1631930543123136e+02L, -0.6058818238834054e+01L}};
    /// y1 = y0 + Σ m_j K_j
    static constexpr long double m[6] = {0.1221224509226641e+01L,
                                         0.6019134481288629e+01L,
                                         0.1253708332932087e+02L,
                                         -0.6878860361058950L,
                                         1.0L,
                                         1.0L};
};

template <class T, class S> class rodas4_stepper;

/// Options: adaptive_options with RODAS4's defaults (facmin 0.2, facmax 6, beta 0) and whether
/// f depends on t.
template <class T> struct rodas4 : adaptive_options<T> {
    /// The floating-point type of the run.
    using scalar = T;
    /// Marks a method the driver accepts (stepper.hpp).
    static constexpr bool is_rotgen_method = true;
    /// Error-controlled: the options are adaptive_options and the stepper has an error estimate.
    static constexpr bool adaptive = true;
    /// The stepper for a system of type S.
    template <class S> using stepper = rodas4_stepper<T, S>;

    bool autonomous = false; ///< true: f does not depend on t, skip ∂f/∂t

    /// calibrate()'s values for scenes (bench/proportionality: rtol means the error at the samples)
    static constexpr double calibrated_scale = 0.6;
    static constexpr double calibrated_power = -1.0 / 4; ///< see calibrated_scale

    rodas4() {
        this->facmin = T(0.2);
        this->facmax = T(6);
        this->beta = T(0);
    }
    /// The defaults with the tolerances rtol, atol.
    rodas4(T rtol, T atol) : rodas4() {
        this->rtol = rtol;
        this->atol = atol;
    }
    /// The method's name, as scene files and `rotgen simulate` spell it.
    std::string name() const { return "rodas4"; }
    /// An empty string when the options are valid, else the reason (one line).
    std::string check() const { return detail::check_adaptive_options<T>(*this); }
};

/// The Rosenbrock method of rotgen.
template <class T> using rosenbrock = rodas4<T>;

/// RODAS4's working storage for one system type S (the stepper concept of stepper.hpp): the
/// Jacobian, ∂f/∂t and an LU factorisation of (I/(γ h) − J) per step.
template <class T, class S> class rodas4_stepper {
  public:
    /// The floating-point type of the run.
    using scalar = T;
    /// The system type S this stepper integrates.
    using system_type = S;
    /// The state vector of S.
    using vector = state_vector<T, S>;
    /// The N×N matrix of the Newton iteration (derivatives.hpp).
    using matrix = jacobian_matrix<T, S>;
    /// The method's coefficients.
    using tab = rodas4_tableau;

    /// What attempt() returns.
    using outcome = step_outcome<T>;

    /// Order p of the step: local error O(h^(p+1)).
    static constexpr int order = 4;
    /// Holds its estimate per unit step under a layout with a span (step_control.hpp).
    static constexpr bool per_unit_step = true;
    /// attempt() returns a weighted error norm (step accepted when <= 1).
    static constexpr bool error_estimate = true;
    /// Samples inside a step come from the driver's cubic Hermite interpolation over
    /// hermite_ends().
    static constexpr dense_kind dense_output = dense_kind::hermite;
    /// Order of the interpolant (local error O(h^(dense_order+1))).
    static constexpr int dense_order = 3;
    /// Evaluates ∂f/∂y (system.jacobian, or finite differences when the system has none).
    static constexpr bool uses_jacobian = true;

    /// Storage for n state components, with the options of m.
    rodas4_stepper(const rodas4<T>& m, std::size_t n)
        : m_atol(m.atol * factor(m)), m_rtol(m.rtol * factor(m)), m_layout(m.layout),
          m_autonomous(m.autonomous), m_y0(vector::Zero(n)), m_y1(m_y0), m_inv(m_y0), m_tmp(m_y0),
          m_rhs(m_y0), m_f0(m_y0), m_f1(m_y0), m_ft(m_y0), m_jac(matrix::Zero(n, n)),
          m_iter(matrix::Zero(n, n)) {
        for (auto& k : m_k)
            k = m_y0;
    }

    /// f(t0, y0), after start() (for the initial step selection).
    const vector& f_start() const { return m_f0; }
    /// The state at t + h of the last attempt().
    const vector& y_new() const { return m_y1; }

    /// Begins a run at (t0, y0): evaluates f(t0, y0); false when it is not finite.
    bool start(const S& sys, T t0, const vector& y0, step_stats& stats) {
        detail::eval_rhs(sys, t0, y0, m_f0, stats);
        m_jac_valid = false;
        return m_f0.allFinite();
    }

    /// One step of size h from (t, y) into y_new(), err the embedded 3rd-order error estimate; code
    /// ok or non_finite.
    outcome attempt(const S& sys, T t, const vector& y, T h, step_stats& stats, bool) {
        m_y0 = y;
        m_t = t;
        m_h = h;
        if (!m_jac_valid) { // J and f_t at (t, y0), kept across rejections
            detail::eval_jacobian(sys, t, y, m_f0, m_jac, stats);
            if (m_autonomous)
                m_ft.setZero();
            else
                detail::eval_time_derivative(sys, t, y, m_ft, m_tmp, stats);
            m_jac_valid = true;
        }
        // M = 1/(hγ) I − J
        m_iter = -m_jac;
        m_iter.diagonal().array() += T(1) / (h * T(tab::gamma));
        m_lu.compute(m_iter);
        ++stats.factorisations;
        for (int i = 0; i < tab::stages; ++i) {
            const auto si = static_cast<std::size_t>(i);
            if (i == 0) {
                m_rhs = m_f0;
            } else {
                m_tmp = y; // y0 + Σ a_ij K_j
                for (int j = 0; j < i; ++j)
                    m_tmp += T(tab::a[i][j]) * m_k[static_cast<std::size_t>(j)];
                detail::eval_rhs(sys, t + T(tab::alpha[i]) * h, m_tmp, m_rhs, stats);
            }
            for (int j = 0; j < i; ++j)
                m_rhs += (T(tab::c[i][j]) / h) * m_k[static_cast<std::size_t>(j)];
            if (!m_autonomous && tab::gamma_i[i] != 0.0L) m_rhs += (h * T(tab::gamma_i[i])) * m_ft;
            m_k[si] = m_lu.solve(m_rhs);
        }
        m_y1 = y;
        for (std::size_t j = 0; j < 6; ++j)
            m_y1 += T(tab::m[j]) * m_k[j];
        const T err = detail::error_norm(m_k[5], y, m_y1, m_atol, m_rtol, m_layout, m_inv) * // K_6
                      detail::unit_step_factor(m_layout, h);
        using std::isfinite;
        if (!isfinite(err) || !m_y1.allFinite()) return {status::non_finite, err};
        return {status::ok, err};
    }

    /// The driver accepted the last attempt: prepares the next step and, when need_dense, the
    /// interpolant; false when f at the new state is not finite.
    bool accept(const S& sys, step_stats& stats, bool /*need_dense*/) {
        // f(t + h, y1): the end slope of the Hermite interpolant and the next first stage
        detail::eval_rhs(sys, m_t + m_h, m_y1, m_f1, stats);
        m_f0.swap(m_f1); // m_f0 = f(t + h, y1), m_f1 = f(t, y0)
        m_jac_valid = false;
        return m_f0.allFinite();
    }

    /// The Hermite data of the last accepted step: y0, f(t, y0) (in m_f1 after the swap in
    /// accept), y1, f(t + h, y1) (in m_f0).
    step_ends<T, vector> hermite_ends() const { return {m_h, m_y0, m_f1, m_y1, m_f0}; }

  private:
    static T factor(const rodas4<T>& m) {
        return calibration_factor(m.calibration_scale, m.calibration_power, m.rtol, m.atol);
    }

    T m_atol, m_rtol;
    error_layout m_layout;
    bool m_autonomous;
    bool m_jac_valid = false;
    T m_t = T(0), m_h = T(0);
    vector m_y0, m_y1, m_inv, m_tmp, m_rhs, m_f0, m_f1, m_ft;
    std::array<vector, 6> m_k;
    matrix m_jac, m_iter;
    Eigen::PartialPivLU<Eigen::Matrix<T, state_dim<S>(), state_dim<S>()>> m_lu;
};

static_assert(check_method<rodas4<double>>());

} // namespace rotgen
