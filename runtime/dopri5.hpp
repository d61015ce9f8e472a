// rotgen runtime — Dormand–Prince 5(4) with PI step-size control and 4th-order dense output.
//
// Method (Dormand & Prince 1980; Hairer, Nørsett & Wanner I, Table II.5.2 and the code DOPRI5):
// 7 stages, the 7th evaluated at the new solution (FSAL: it is the next step's 1st stage),
// so 6 evaluations of f per step. The solution y1 is the 5th-order one (local extrapolation);
// the difference to the embedded 4th-order solution is the error estimate
//   err_vec = h·Σ e_i k_i,   err = RMS_i err_vec_i / (atol + rtol·max(|y0_i|, |y1_i|)),
// err = O(h^5), so the controller exponent is 1/5 (see step_control.hpp, q = 5).
// Dense output (Shampine 1986, as in DOPRI5's CONTD5), θ = (t − t_n)/h ∈ [0, 1]:
//   y(θ) = r1 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ) r5)))
//   r1 = y0, r2 = y1 − y0, r3 = h k1 − r2, r4 = r2 − h k7 − r3, r5 = h Σ d_i k_i
// a continuous extension of order 4 (local error O(h^5)), at no extra evaluations of f.
#pragma once

#include <cmath>
#include <string>

#include "derivatives.hpp"
#include "integrate.hpp"
#include "step_control.hpp"
#include "system.hpp"

namespace rotgen {

// Butcher tableau of DOPRI5 (exact rationals, evaluated in long double).
struct dopri5_tableau {
    static constexpr long double c2 = 1.0L / 5, c3 = 3.0L / 10, c4 = 4.0L / 5, c5 = 8.0L / 9;
    static constexpr long double a21 = 1.0L / 5;
    static constexpr long double a31 = 3.0L / 40, a32 = 9.0L / 40;
    static constexpr long double a41 = 44.0L / 45, a42 = -56.0L / 15, a43 = 32.0L / 9;
    static constexpr long double a51 = 19372.0L / 6561, a52 = -25360.0L / 2187,
                                 a53 = 64448.0L / 6561, a54 = -212.0L / 729;
    static constexpr long double a61 = 9017.0L / 3168, a62 = -355.0L / 33, a63 = 46732.0L / 5247,
                                 a64 = 49.0L / 176, a65 = -5103.0L / 18656;
    // 5th-order weights b_i = a7i (b2 = 0)
    static constexpr long double a71 = 35.0L / 384, a73 = 500.0L / 1113, a74 = 125.0L / 192,
                                 a75 = -2187.0L / 6784, a76 = 11.0L / 84;
    // e_i = b_i − b̂_i (5th minus embedded 4th order)
    static constexpr long double e1 = 71.0L / 57600, e3 = -71.0L / 16695, e4 = 71.0L / 1920,
                                 e5 = -17253.0L / 339200, e6 = 22.0L / 525, e7 = -1.0L / 40;
    // dense output
    static constexpr long double d1 = -12715105075.0L / 11282082432,
                                 d3 = 87487479700.0L / 32700410799,
                                 d4 = -10690763975.0L / 1880347072,
                                 d5 = 701980252875.0L / 199316789632,
                                 d6 = -1453857185.0L / 822651844, d7 = 69997945.0L / 29380423;
};

template <class T, class S> class dopri5_stepper;

// Options: adaptive_options with DOPRI5's defaults (safety 0.9, facmin 0.2, facmax 10, beta 0.04).
template <class T> struct dopri5 : adaptive_options<T> {
    using scalar = T;
    static constexpr bool is_rotgen_method = true;
    static constexpr bool adaptive = true;
    template <class S> using stepper = dopri5_stepper<T, S>;

    dopri5() = default;
    dopri5(T rtol, T atol) {
        this->rtol = rtol;
        this->atol = atol;
    }
    std::string name() const { return "dopri5"; }
    std::string check() const { return detail::check_adaptive_options<T>(*this); }
};

template <class T, class S> class dopri5_stepper {
  public:
    using vector = state_vector<T, S>;
    using tab = dopri5_tableau;

    dopri5_stepper(const dopri5<T>& m, std::size_t n)
        : m_atol(m.atol), m_rtol(m.rtol), m_y0(vector::Zero(n)), m_y1(m_y0), m_tmp(m_y0),
          m_k1(m_y0), m_k2(m_y0), m_k3(m_y0), m_k4(m_y0), m_k5(m_y0), m_k6(m_y0), m_k7(m_y0),
          m_r2(m_y0), m_r3(m_y0), m_r4(m_y0), m_r5(m_y0) {}

    int order() const { return 5; }
    const vector& f_start() const { return m_k1; }
    const vector& y_new() const { return m_y1; }

    bool start(const S& sys, T t0, const vector& y0, step_stats& stats) {
        detail::eval_rhs(sys, t0, y0, m_k1, stats); // k1 = f(t0, y0)
        return m_k1.allFinite();
    }

    struct outcome {
        status code;
        T err;
    };

    outcome attempt(const S& sys, T t, const vector& y, T h, step_stats& stats) {
        m_y0 = y;
        m_h = h;
        m_tmp = y + h * T(tab::a21) * m_k1;
        detail::eval_rhs(sys, t + T(tab::c2) * h, m_tmp, m_k2, stats);
        m_tmp = y + h * (T(tab::a31) * m_k1 + T(tab::a32) * m_k2);
        detail::eval_rhs(sys, t + T(tab::c3) * h, m_tmp, m_k3, stats);
        m_tmp = y + h * (T(tab::a41) * m_k1 + T(tab::a42) * m_k2 + T(tab::a43) * m_k3);
        detail::eval_rhs(sys, t + T(tab::c4) * h, m_tmp, m_k4, stats);
        m_tmp = y + h * (T(tab::a51) * m_k1 + T(tab::a52) * m_k2 + T(tab::a53) * m_k3 +
                         T(tab::a54) * m_k4);
        detail::eval_rhs(sys, t + T(tab::c5) * h, m_tmp, m_k5, stats);
        m_tmp = y + h * (T(tab::a61) * m_k1 + T(tab::a62) * m_k2 + T(tab::a63) * m_k3 +
                         T(tab::a64) * m_k4 + T(tab::a65) * m_k5);
        detail::eval_rhs(sys, t + h, m_tmp, m_k6, stats);
        // y1 = y0 + h Σ b_i k_i   (5th order)
        m_y1 = y + h * (T(tab::a71) * m_k1 + T(tab::a73) * m_k3 + T(tab::a74) * m_k4 +
                        T(tab::a75) * m_k5 + T(tab::a76) * m_k6);
        detail::eval_rhs(sys, t + h, m_y1, m_k7, stats); // k7 = f(t + h, y1), FSAL
        // err_vec = h Σ e_i k_i
        m_tmp = h * (T(tab::e1) * m_k1 + T(tab::e3) * m_k3 + T(tab::e4) * m_k4 + T(tab::e5) * m_k5 +
                     T(tab::e6) * m_k6 + T(tab::e7) * m_k7);
        const T err = detail::error_norm(m_tmp, y, m_y1, m_atol, m_rtol);
        using std::isfinite;
        if (!isfinite(err) || !m_y1.allFinite() || !m_k7.allFinite())
            return {status::non_finite, err};
        return {status::ok, err};
    }

    bool accept(const S&, step_stats&, bool need_dense) {
        if (need_dense) {
            // r2 = y1 − y0, r3 = h k1 − r2, r4 = r2 − h k7 − r3, r5 = h Σ d_i k_i
            m_r2 = m_y1 - m_y0;
            m_r3 = m_h * m_k1 - m_r2;
            m_r4 = m_r2 - m_h * m_k7 - m_r3;
            m_r5 = m_h * (T(tab::d1) * m_k1 + T(tab::d3) * m_k3 + T(tab::d4) * m_k4 +
                          T(tab::d5) * m_k5 + T(tab::d6) * m_k6 + T(tab::d7) * m_k7);
        }
        m_k1.swap(m_k7); // FSAL: f(t + h, y1) is the next step's first stage
        return true;
    }

    // y(t_n + θh) = r1 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ) r5))), valid after accept(…, true)
    void dense(T theta, vector& out) const {
        const T th1 = T(1) - theta;
        out = m_y0 + theta * (m_r2 + th1 * (m_r3 + theta * (m_r4 + th1 * m_r5)));
    }

  private:
    T m_atol, m_rtol;
    T m_h = T(0);
    vector m_y0, m_y1, m_tmp, m_k1, m_k2, m_k3, m_k4, m_k5, m_k6, m_k7, m_r2, m_r3, m_r4, m_r5;
};

} // namespace rotgen
