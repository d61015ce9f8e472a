/// \file
/// rotgen runtime — Dormand–Prince 5(4) with PI step-size control and 4th-order dense output.
///
/// Method (Dormand & Prince 1980; Hairer, Nørsett & Wanner I, Table II.5.2 and the code DOPRI5):
/// 7 stages, the 7th evaluated at the new solution (FSAL: it is the next step's 1st stage),
/// so 6 evaluations of f per step. The solution y1 is the 5th-order one (local extrapolation);
/// the difference to the embedded 4th-order solution is the error estimate
///   err_vec = h·Σ e_i k_i,   err = RMS_i err_vec_i / (atol + rtol·max(|y0_i|, |y1_i|)),
/// err = O(h^5), so the controller exponent is 1/5 (see step_control.hpp, q = 5).
/// Dense output (Shampine 1986, as in DOPRI5's CONTD5), θ = (t − t_n)/h ∈ [0, 1]:
///   y(θ) = r1 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ) r5)))
///   r1 = y0, r2 = y1 − y0, r3 = h k1 − r2, r4 = r2 − h k7 − r3, r5 = h Σ d_i k_i
/// a continuous extension of order 4 (local error O(h^5)), at no extra evaluations of f.
/// Stepper concept (stepper.hpp): order 5, error estimate, own dense output of order 4, no
/// Jacobian.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "../combine.hpp"
#include "../derivatives.hpp"
#include "../step_control.hpp"
#include "../stepper.hpp"

namespace rotgen {

/// Butcher tableau of DOPRI5 (exact rationals, evaluated in long double).
struct dopri5_tableau {
    /// \name Coefficients
    ///@{

    /// The nodes c_i, the stages' a_ij, the weights b_i, the error weights e_i and the dense
    /// output's d_i.
    static constexpr long double c2 = 1.0L / 5, c3 = 3.0L / 10, c4 = 4.0L / 5, c5 = 8.0L / 9;
    static constexpr long double a21 = 1.0L / 5;
    static constexpr long double a31 = 3.0L / 40, a32 = 9.0L / 40;
    static constexpr long double a41 = 44.0L / 45, a42 = -56.0L / 15, a43 = 32.0L / 9;
    static constexpr long double a51 = 19372.0L / 6561, a52 = -25360.0L / 2187,
                                 a53 = 64448.0L / 6561, a54 = -212.0L / 729;
    static constexpr long double a61 = 9017.0L / 3168, a62 = -355.0L / 33, a63 = 46732.0L / 5247,
                                 a64 = 49.0L / 176, a65 = -5103.0L / 18656;
    /// 5th-order weights b_i = a7i (b2 = 0)
    static constexpr long double a71 = 35.0L / 384, a73 = 500.0L / 1113, a74 = 125.0L / 192,
                                 a75 = -2187.0L / 6784, a76 = 11.0L / 84;
    /// e_i = b_i − b̂_i (5th minus embedded 4th order)
    static constexpr long double e1 = 71.0L / 57600, e3 = -71.0L / 16695, e4 = 71.0L / 1920,
                                 e5 = -17253.0L / 339200, e6 = 22.0L / 525, e7 = -1.0L / 40;
    /// dense output
    static constexpr long double d1 = -12715105075.0L / 11282082432,
                                 d3 = 87487479700.0L / 32700410799,
                                 d4 = -10690763975.0L / 1880347072,
                                 d5 = 701980252875.0L / 199316789632,
                                 d6 = -1453857185.0L / 822651844, d7 = 69997945.0L / 29380423;
    ///@}
};

template <class T, class S> class dopri5_stepper;

/// Options: adaptive_options with DOPRI5's defaults (safety 0.9, facmin 0.2, facmax 10, beta 0.04).
template <class T> struct dopri5 : adaptive_options<T> {
    using scalar = T; ///< the floating-point type of the run
    /// Marks a method the driver accepts (stepper.hpp).
    static constexpr bool is_rotgen_method = true;
    /// Error-controlled: the options are adaptive_options and the stepper has an error estimate.
    static constexpr bool adaptive = true;
    /// The stepper for a system of type S.
    template <class S> using stepper = dopri5_stepper<T, S>;

    /// calibrate()'s values for scenes (bench/proportionality: rtol means the error at the samples)
    static constexpr double calibrated_scale = 0.5;
    static constexpr double calibrated_power = -1.0 / 5; ///< see calibrated_scale

    dopri5() = default;
    /// The defaults with the tolerances rtol, atol.
    dopri5(T rtol, T atol) {
        this->rtol = rtol;
        this->atol = atol;
    }
    /// The method's name, as scene files and `rotgen simulate` spell it.
    std::string name() const { return "dopri5"; }
    /// An empty string when the options are valid, else the reason (one line).
    std::string check() const { return detail::check_adaptive_options<T>(*this); }
};

/// DOPRI5's working storage for one system type S (the stepper concept of stepper.hpp; the method
/// in the file's comment).
template <class T, class S> class dopri5_stepper {
  public:
    /// The floating-point type of the run.
    using scalar = T;
    /// The system type S this stepper integrates.
    using system_type = S;
    /// The state vector of S.
    using vector = state_vector<T, S>;
    using work = detail::work_vector<T, S>; ///< see combine.hpp
    /// The method's coefficients.
    using tab = dopri5_tableau;

    /// What attempt() returns.
    using outcome = step_outcome<T>;

    /// Order p of the step: local error O(h^(p+1)).
    static constexpr int order = 5;
    /// Holds its estimate per unit step under a layout with a span (step_control.hpp).
    static constexpr bool per_unit_step = true;
    /// attempt() returns a weighted error norm (step accepted when <= 1).
    static constexpr bool error_estimate = true;
    /// Samples inside a step come from the stepper's own interpolant, dense().
    static constexpr dense_kind dense_output = dense_kind::continuous_extension;
    /// Order of the interpolant (local error O(h^(dense_order+1))).
    static constexpr int dense_order = 4;
    /// Never evaluates ∂f/∂y.
    static constexpr bool uses_jacobian = false;

    /// Storage for n state components, with the tolerances of m.
    dopri5_stepper(const dopri5<T>& m, std::size_t n)
        : m_atol(m.atol * factor(m)), m_rtol(m.rtol * factor(m)), m_layout(m.layout) {
        const auto zero = detail::make_work_vector<work>(n);
        m_y0 = m_y1 = m_r2 = m_r3 = m_r4 = m_r5 = m_y0_scratch = m_arg_scratch = m_inv = zero;
        m_k.fill(zero);
    }

    /// f(t0, y0), after start() (for the initial step selection).
    const work& f_start() const { return m_k[0]; }
    /// The state at t + h of the last attempt().
    const work& y_new() const { return m_y1; }

    /// Begins a run at (t0, y0): evaluates f(t0, y0); false when it is not finite.
    bool start(const S& sys, T t0, const vector& y0, step_stats& stats) {
        work y = m_y0;
        detail::assign(y, y0);
        detail::eval_rhs(sys, t0, y, m_k[0], stats); // k1 = f(t0, y0)
        return detail::all_finite(m_k[0]);
    }

    /// One step of size h from (t, y): stages 2..7 (k7 = f(t + h, y1), FSAL), y1 and the error
    /// estimate (see combine.hpp for where the stages are kept).
    ROTGEN_ALWAYS_INLINE outcome attempt(const S& sys, T t, const vector& y, T h, step_stats& stats,
                                         bool need_dense) {
        m_h = h;
        if constexpr (static_state_size<S>() > 0) {
            if (need_dense) return attempt_keeping_stages(sys, t, y, h, stats);
            stages local;
            local[0] = m_k[0];
            const outcome out = steps(sys, t, y, h, stats, local);
            m_k[6] = local[6];
            return out;
        } else {
            return steps(sys, t, y, h, stats, m_k);
        }
    }

    /// The driver accepted the last attempt: f(t + h, y1), the last stage, becomes the next step's
    /// first (FSAL) and, when need_dense, the interpolant is prepared; always true.
    ROTGEN_ALWAYS_INLINE bool accept(const S&, step_stats&, bool need_dense) {
        if (need_dense) prepare_dense();
        m_k[0] = m_k[6]; // FSAL: f(t + h, y1) is the next step's first stage
        return true;
    }

    /// y(t_n + θh) = r1 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ) r5))), valid after accept(…, true)
    void dense(T theta, vector& out) const {
        const T th1 = T(1) - theta;
        for (std::size_t i = 0; i < detail::size_of(m_y0); ++i)
            out[static_cast<Eigen::Index>(i)] =
                m_y0[i] + theta * (m_r2[i] + th1 * (m_r3[i] + theta * (m_r4[i] + th1 * m_r5[i])));
    }

  private:
    using stages = std::array<work, 7>; ///< k1..k7

    ROTGEN_COLD outcome attempt_keeping_stages(const S& sys, T t, const vector& y, T h,
                                               step_stats& stats) {
        return steps(sys, t, y, h, stats, m_k);
    }

    /// Stages 2..7, y1 and the error estimate, with the stages in k (k[0] holds k1).
    ROTGEN_ALWAYS_INLINE outcome steps(const S& sys, T t, const vector& y, T h, step_stats& stats,
                                       stages& k) {
        if constexpr (static_state_size<S>() > 0) {
            work y0 = k[0], arg = k[0]; // locals: kept in registers
            return stages_from(sys, t, y, h, stats, k, y0, arg);
        } else { // the stepper's own: no allocation per step
            return stages_from(sys, t, y, h, stats, k, m_y0_scratch, m_arg_scratch);
        }
    }

    /// The same, with y0 and the stage argument in `y0` and `arg`.
    ROTGEN_ALWAYS_INLINE outcome stages_from(const S& sys, T t, const vector& y, T h,
                                             step_stats& stats, stages& k, work& y0, work& arg) {
        using detail::stage;
        detail::assign(y0, y);
        auto f = [&](int i, long double c, const work& at) {
            detail::eval_rhs(sys, t + T(c) * h, at, k[static_cast<std::size_t>(i - 1)], stats);
        };
        auto a = [&](long double coefficient, int j) {
            return detail::make_term<T>(coefficient, k[static_cast<std::size_t>(j - 1)]);
        };
        stage(arg, y0, h, a(tab::a21, 1));
        f(2, tab::c2, arg);
        stage(arg, y0, h, a(tab::a32, 2), a(tab::a31, 1));
        f(3, tab::c3, arg);
        stage(arg, y0, h, a(tab::a43, 3), a(tab::a41, 1), a(tab::a42, 2));
        f(4, tab::c4, arg);
        stage(arg, y0, h, a(tab::a54, 4), a(tab::a51, 1), a(tab::a52, 2), a(tab::a53, 3));
        f(5, tab::c5, arg);
        stage(arg, y0, h, a(tab::a65, 5), a(tab::a61, 1), a(tab::a62, 2), a(tab::a63, 3),
              a(tab::a64, 4));
        f(6, 1.0L, arg);
        // y1 = y0 + h Σ b_i k_i (5th order); k7 = f(t + h, y1) (FSAL)
        stage(m_y1, y0, h, a(tab::a76, 6), a(tab::a71, 1), a(tab::a73, 3), a(tab::a74, 4),
              a(tab::a75, 5));
        f(7, 1.0L, m_y1);
        // err_vec = h Σ e_j k_j (into arg, free now);  err = its RMS norm (step_control.hpp)
        detail::combination(arg, a(tab::e1, 1), a(tab::e3, 3), a(tab::e4, 4), a(tab::e5, 5),
                            a(tab::e6, 6), a(tab::e7, 7));
        for (auto& e : arg)
            e *= h;
        const T err = detail::error_norm(arg, y0, m_y1, m_atol, m_rtol, m_layout, m_inv) *
                      detail::unit_step_factor(m_layout, h);
        m_y0 = y0;
        using std::isfinite;
        if (!isfinite(err) || !detail::all_finite(m_y1) || !detail::all_finite(k[6]))
            return {status::non_finite, err};
        return {status::ok, err};
    }

    /// r2 = y1 − y0, r3 = h k1 − r2, r4 = r2 − h k7 − r3, r5 = h Σ d_i k_i
    ROTGEN_COLD void prepare_dense() {
        const auto& k = m_k;
        for (std::size_t i = 0; i < detail::size_of(m_y0); ++i) {
            m_r2[i] = m_y1[i] - m_y0[i];
            m_r3[i] = m_h * k[0][i] - m_r2[i];
            m_r4[i] = m_r2[i] - m_h * k[6][i] - m_r3[i];
            m_r5[i] = m_h * (T(tab::d1) * k[0][i] + T(tab::d3) * k[2][i] + T(tab::d4) * k[3][i] +
                             T(tab::d5) * k[4][i] + T(tab::d6) * k[5][i] + T(tab::d7) * k[6][i]);
        }
    }

    static T factor(const dopri5<T>& m) {
        return calibration_factor(m.calibration_scale, m.calibration_power, m.rtol, m.atol);
    }

    T m_atol, m_rtol;
    error_layout m_layout;
    T m_h = T(0);
    work m_y0, m_y1, m_r2, m_r3, m_r4, m_r5;
    work m_inv; ///< weight_i / sk_i of the last step (step_control.hpp, error_layout)
    stages m_k; ///< the last step's stages (static size: k1 and k7, all in steps with samples)
    work m_y0_scratch, m_arg_scratch; ///< a run-time size's y0 and stage argument in a step
};

static_assert(check_method<dopri5<double>>());

} // namespace rotgen
