/// \file
/// rotgen runtime — error norm, PI step-size controller and initial step selection for the
/// adaptive methods (Hairer, Nørsett & Wanner, Solving ODEs I, §II.4; the codes DOPRI5/DOP853).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "combine.hpp"
#include "derivatives.hpp"
#include "result.hpp"

namespace rotgen {

/// What a tolerance means: one definition for every method (docs/integrators.md, "What a tolerance
/// means"). Component i of the state may err by
///   sk_i = atol + rtol · m_i,
/// m_i the magnitude of what the component measures, by its group:
///   groups empty             m_i = max(|y0_i|, |y1_i|): each component relative to itself
///                            (HNW I, (4.10); C++ systems that say nothing about their layout)
///   groups[i] = attitude     m_i = 1: an angle or a unit quaternion's component, whose error is
///                            an attitude error in radians however far the angle has turned (an
///                            Euler angle of a fast top grows to 1e4 rad; relative to it, rtol
///                            would allow 1e4 · rtol)
///   groups[i] = itself       m_i = max(|y0_i|, |y1_i|), as without groups (a component the
///                            layout does not describe, e.g. one appended to a form's state)
///   groups[i] = g in 0..7    m_i = max(‖y0_g‖, ‖y1_g‖), the Euclidean norm of group g's
///   components:
///                            a rate or a momentum relative to its vector (ω, the angles' rates,
///                            the momenta), not to itself (ω1 of a fast top is 1e-3 of |ω|)
/// weights[i] (empty: all 1) multiplies err_i / sk_i; 0 leaves a component out of the norm. The
/// weighted error vector's RMS over the components is the step's error (error_norm below); each
/// method holds its estimate of it to its calibration of rtol (the method's `tolerance_scale`).
/// A lane system (lanes.hpp: W lanes, component-major) applies the layout of one lane to each.
///
/// span > 0 (calibrate() requires it): the error per unit step. A step of size h is held to the
/// share |h| / span of the tolerance (unit_step_factor), so that the local errors of a run over
/// `span` add up to about the tolerance however many steps it takes: a fast top's steps follow its
/// spin, and held per step, the error grew with it (DOP853 on the body form: 1.3 rtol at spin 10,
/// 33 rtol at spin 1000; bench/results/proportionality.md). 0: each step to the whole tolerance
/// (HNW I's error per step), the default of a C++ run that is not calibrated.
struct error_layout {
    static constexpr signed char attitude = -1; ///< the group of an attitude component (m_i = 1)
    static constexpr signed char itself = -2;   ///< relative to itself (m_i = |y_i|)
    static constexpr int max_groups = 8;        ///< vector groups 0 .. max_groups - 1
    std::vector<signed char> groups;            ///< per component of one lane's state, or empty
    std::vector<double> weights;                ///< per component of one lane's state, or empty
    double span = 0; ///< > 0: the time span the tolerance holds over (error per unit step)
};

/// Options shared by the adaptive methods. Each method sets its own defaults in its header.
template <class T> struct adaptive_options {
    T rtol = T(1e-6);    ///< relative tolerance, >= 10·eps(T) (or 0 with atol > 0)
    T atol = T(1e-9);    ///< absolute tolerance, >= 0
    T h0 = T(0);         ///< initial step; 0 selects it automatically (hinit below)
    T hmax = T(0);       ///< largest step; 0 means |t_end − t0|
    T fixed_step = T(0); ///< > 0: no error control, steps of this size (order studies, benches)
    T safety = T(0.9);   ///< safety factor of the controller
    T facmin = T(0.2);   ///< smallest step-size ratio h_new/h
    T facmax = T(10);    ///< largest step-size ratio h_new/h
    T beta = T(0.04);    ///< PI controller weight of the previous error (0: I controller)
    std::size_t max_steps = 1000000; ///< attempted steps before status::max_steps
    error_layout layout;             ///< what the tolerance is relative to (error_layout)
    /// The estimate is held to F · sk, F = calibration_scale · τ^calibration_power (τ = rtol, or
    /// atol when rtol is 0; calibration_factor): 1 and 0 by default; calibrate() sets each
    /// method's measured values, so that the error at the samples is near rtol whatever the method.
    T calibration_scale = T(1);
    T calibration_power = T(0); ///< see calibration_scale
};

/// F = scale · τ^power, τ = rtol (atol when rtol is 0), and at least 4 eps / τ (an estimate held
/// below rounding would stop the run): the factor a method's estimate is held to (calibrate()).
template <class T> T calibration_factor(T scale, T power, T rtol, T atol) {
    using std::max;
    using std::pow;
    const T tau = rtol > T(0) ? rtol : atol;
    if (!(tau > T(0))) return scale;
    const T f = power == T(0) ? scale : scale * pow(tau, power);
    return max(f, T(4) * std::numeric_limits<T>::epsilon() / tau);
}

/// Gives the method m the layout of its system's state and its calibration, M::calibrated_scale
/// and M::calibrated_power (measured: bench/proportionality/measure.py), so that rtol means the
/// same for every method (error_layout; docs/integrators.md, "What a tolerance means"). The scene
/// layer calls it for every run; a C++ program may, or keep the plain per-component norm.
/// The layout's span must be the run's |t_end − t0| (> 0): the calibration holds per unit step.
template <class M> void calibrate(M& m, const error_layout& layout) {
    if (!(layout.span > 0) || !std::isfinite(layout.span))
        throw std::invalid_argument(
            "calibrate: the layout's span must be the run's time span, > 0");
    m.layout = layout;
    m.calibration_scale = M::calibrated_scale;
    m.calibration_power = M::calibrated_power;
}

namespace detail {

/// What a step's error estimate is multiplied by before the controller compares it with 1:
/// span / |h| under the error per unit step (error_layout::span > 0), else 1.
template <class T> T unit_step_factor(const error_layout& L, T h) {
    using std::abs;
    return L.span > 0 ? T(L.span) / abs(h) : T(1);
}

/// The largest of ‖a_g‖ and ‖b_g‖ for each group g of one lane (components c·lanes + lane).
template <class T, class A, class B>
std::array<T, error_layout::max_groups> group_norms(const error_layout& L, const A& a, const B& b,
                                                    std::size_t lanes, std::size_t lane) {
    using std::max;
    using std::sqrt;
    std::array<T, error_layout::max_groups> sa{}, sb{};
    for (std::size_t c = 0; c < L.groups.size(); ++c) {
        const int g = L.groups[c];
        if (g < 0 || g >= error_layout::max_groups) continue;
        const T ai = a[c * lanes + lane], bi = b[c * lanes + lane];
        sa[std::size_t(g)] += ai * ai;
        sb[std::size_t(g)] += bi * bi;
    }
    for (std::size_t g = 0; g < sa.size(); ++g)
        sa[g] = max(sqrt(sa[g]), sqrt(sb[g]));
    return sa;
}

/// out_i = weight_i / sk_i for every component of a state of `lanes` lanes (1: an ordinary
/// system), sk_i = atol + rtol · m_i as error_layout defines it, from the step's start y0 and end
/// y1. A layout whose size is not the lane's component count is ignored (each component relative
/// to itself).
template <class T, class A, class B, class Out>
void inverse_scales(const error_layout& L, const A& y0, const B& y1, T atol, T rtol,
                    std::size_t lanes, Out& out) {
    using std::abs;
    using std::max;
    const T tiny = std::numeric_limits<T>::min();
    const std::size_t n = size_of(out), per_lane = n / lanes;
    const bool grouped = L.groups.size() == per_lane;
    const bool weighted = L.weights.size() == per_lane;
    for (std::size_t l = 0; l < lanes; ++l) {
        std::array<T, error_layout::max_groups> norms{};
        if (grouped) norms = group_norms<T>(L, y0, y1, lanes, l);
        for (std::size_t c = 0; c < per_lane; ++c) {
            const std::size_t i = c * lanes + l;
            T m = max(abs(y0[i]), abs(y1[i]));
            const int g = grouped ? L.groups[c] : error_layout::itself;
            if (g == error_layout::attitude) m = T(1);
            if (g >= 0) m = norms[std::size_t(g)];
            const T w = weighted ? T(L.weights[c]) : T(1);
            out[i] = w / max(atol + rtol * m, tiny);
        }
    }
}

/// Error norm (HNW I, (4.11)): RMS over i of err_i · inv_i, inv_i = weight_i / sk_i from
/// inverse_scales. Any vectors with size() and operator[] (Eigen vectors, the explicit methods'
/// work vectors).
template <class T, class E, class V> T error_norm(const E& err, const V& inv) {
    using std::sqrt;
    T sum = T(0);
    for (std::size_t i = 0; i < size_of(err); ++i) {
        const T r = err[i] * inv[i];
        sum += r * r;
    }
    return sqrt(sum / T(size_of(err)));
}

/// The same with the scales of y0, y1 under the layout (into the work vector `inv`).
template <class T, class E, class V, class W>
T error_norm(const E& err, const V& y0, const W& y1, T atol, T rtol, const error_layout& layout,
             W& inv) {
    inverse_scales(layout, y0, y1, atol, rtol, 1, inv);
    return error_norm<T>(err, inv);
}

/// True for a stepper that holds its estimate per unit step under a layout with a span
/// (unit_step_factor: DOP853, DOPRI5, RODAS4); the split methods' steppers hold theirs per step.
template <class St, class = void> struct per_unit_step : std::false_type {};
template <class St>
struct per_unit_step<St, std::enable_if_t<St::per_unit_step>> : std::true_type {};

/// Under the error per unit step the share of a step shrinks with it, and so does the error that
/// f's own rounding makes in it (near gimbal lock, φ' = (p_φ − p_ψ cos θ) / (A sin²θ) loses 8
/// digits at θ = 1e-4; at spin 1e6, ψ's ulps are 1e-10 rad): no step may then meet its share, and
/// the controller would reject ever shorter ones (10^7 attempts without reaching t = 11 of 40). The
/// adaptive loop puts a floor under the share when the estimate shows rounding:
///   - a rejected attempt whose estimate is still half the previous rejected one's or more though
///     the step shrank to 0.8 of it or less: the floor becomes the share of the first step tried
///     at this time (the estimate does not fall with h: it is not truncation);
///   - a third or more of the recent attempts rejected (a moving average over about 50): the floor
///     doubles, from the share of the step then, every 50 attempts while it lasts.
/// The run goes on held per step at that floor, as HNW's error per step holds it.
template <class T> class share_floor {
  public:
    /// The floor of a run under the layout (none without a span).
    explicit share_floor(const error_layout& layout)
        : m_span(layout.span > 0 ? T(layout.span) : T(0)) {}

    /// The estimate err of an attempt of size h with its share held at the floor.
    T held(T h, T err) const {
        using std::abs;
        using std::min;
        return m_floor > T(0) ? err * min(T(1), abs(h) / (m_span * m_floor)) : err;
    }

    /// Counts an attempt of size h with estimate err (held), rejected or not, and raises the
    /// floor where it shows rounding.
    void attempted(T h, T err, bool rejected) {
        using std::abs;
        using std::max;
        if (!(m_span > T(0))) return;
        if (rejected && m_chain > 0 && err >= m_last_err / T(2) && abs(h) <= T(0.8) * m_last_h)
            m_floor = max(m_floor, m_first_h / m_span);
        if (rejected && m_chain++ == 0) m_first_h = abs(h);
        if (!rejected) m_chain = 0;
        m_last_h = abs(h), m_last_err = err;
        m_rate += T(0.02) * ((rejected ? T(1) : T(0)) - m_rate);
        if (++m_since < 50 || m_rate < T(1) / T(3)) return;
        m_floor = max(T(2) * m_floor, abs(h) / m_span);
        m_since = 0;
    }

  private:
    T m_span, m_floor = T(0), m_rate = T(0);
    T m_first_h = T(0), m_last_h = T(0), m_last_err = T(0);
    std::size_t m_since = 0, m_chain = 0;
};

/// Validation of the options shared by the adaptive methods; returns an empty string when valid.
template <class T> std::string check_adaptive_options(const adaptive_options<T>& o) {
    using std::isfinite;
    const T eps = std::numeric_limits<T>::epsilon();
    if (!(o.fixed_step >= T(0)) || !isfinite(o.fixed_step)) return "fixed_step must be >= 0";
    if (o.fixed_step > T(0)) return "";
    if (!(o.rtol >= T(0)) || !(o.atol >= T(0)) || !isfinite(o.rtol) || !isfinite(o.atol))
        return "tolerances must be finite and >= 0";
    if (o.rtol == T(0) && o.atol == T(0)) return "rtol and atol are both 0";
    if (o.rtol != T(0) && o.rtol < T(10) * eps)
        return "rtol is below 10*epsilon of the scalar type; use a wider scalar or a looser rtol";
    if (!(o.h0 >= T(0)) || !(o.hmax >= T(0))) return "h0 and hmax must be >= 0";
    if (!(o.safety > T(0) && o.safety < T(1))) return "safety must lie in (0, 1)";
    if (!(o.facmin > T(0) && o.facmin < T(1))) return "facmin must lie in (0, 1)";
    if (!(o.facmax > T(1))) return "facmax must be > 1";
    if (!(o.beta >= T(0) && o.beta < T(0.2))) return "beta must lie in [0, 0.2)";
    return "";
}

/// PI controller (HNW I, (4.13) and the code DOPRI5):
///   fac11 = err^alpha,  alpha = 1/q − 0.75·beta,  q = order of the error estimate + 1
///   accepted (err <= 1): h_new = h · clamp(safety / (fac11 · err_old^(−beta)), facmin, facmax),
///                        err_old = max(err, 1e-4); no growth right after a rejection
///   rejected (err > 1):  h_new = h · max(facmin, safety / fac11)
template <class T> class pi_controller {
  public:
    pi_controller(const adaptive_options<T>& o, int q)
        : m_safety(o.safety), m_facmin(o.facmin), m_facmax(o.facmax), m_beta(o.beta),
          m_alpha(T(1) / T(q) - T(0.75) * o.beta), m_eighth_root(o.beta == T(0) && q == 8) {}

    /// New step after an accepted step of size h with error err (<= 1).
    T accepted(T h, T err) {
        using std::max;
        using std::min;
        using std::pow;
        const T fac11 = power_alpha(err);
        // = 1/fac of the Fortran code; err_old^beta is 1 for the I controller (beta = 0)
        T ratio = m_safety / (m_beta == T(0) ? fac11 : fac11 / pow(m_err_old, m_beta));
        if (!(ratio == ratio) || fac11 == T(0)) ratio = m_facmax;
        ratio = min(m_facmax, max(m_facmin, ratio));
        if (m_rejected) ratio = min(ratio, T(1));
        m_err_old = max(err, T(1e-4));
        m_rejected = false;
        return h * ratio;
    }

    /// New step after a rejected step of size h with error err (> 1, or non-finite).
    T rejected(T h, T err) {
        using std::isfinite;
        using std::max;
        m_rejected = true;
        if (!isfinite(err)) return h * T(0.25);
        return h * max(m_facmin, m_safety / power_alpha(err));
    }

  private:
    /// err^alpha. The next step waits for this on every step, so DOP853's exponent 1/8 is taken as
    /// three square roots (within 2 ulp of pow, at about half its latency; measured: 2 µs of 40 on
    /// the free top at tol 1e-10).
    T power_alpha(T err) const {
        using std::pow;
        using std::sqrt;
        return m_eighth_root ? sqrt(sqrt(sqrt(err))) : pow(err, m_alpha);
    }

    T m_safety, m_facmin, m_facmax, m_beta, m_alpha;
    bool m_eighth_root;
    T m_err_old = T(1e-4);
    bool m_rejected = false;
};

/// Initial step (HNW I, §II.4, "Starting step size"; the routine HINIT of DOPRI5), with `order`
/// the order of the method. `f0` = f(t0, y0), `dir` = ±1, `hmax` > 0.
///   d0 = ‖y0‖, d1 = ‖f0‖ (weighted RMS norms);  h = 0.01·d0/d1 (or 1e-6 if either is tiny)
///   explicit Euler step to y1, d2 = ‖f(t0 + h, y1) − f0‖ / h
///   h1 = (0.01 / max(d1, d2))^(1/order)  (or max(1e-6, 1e-3·h) if both are tiny)
///   h  = min(100·h, h1, hmax)
template <class S, class T, class V, class F>
T initial_step(const S& sys, T t0, const V& y0, const F& f0, T dir, T hmax, T atol, T rtol,
               int order, step_stats& stats, const error_layout& layout = {}) {
    using std::abs;
    using std::max;
    using std::min;
    using std::pow;
    using std::sqrt;
    const T n = T(y0.size());
    F inv = f0; // weight_i / sk_i at y0 (error_layout)
    inverse_scales(layout, y0, y0, atol, rtol, 1, inv);
    T dnf = T(0), dny = T(0);
    for (std::size_t i = 0; i < size_of(f0); ++i) {
        const T y0i = y0[static_cast<Eigen::Index>(i)];
        dnf += (f0[i] * inv[i]) * (f0[i] * inv[i]);
        dny += (y0i * inv[i]) * (y0i * inv[i]);
    }
    dnf /= n;
    dny /= n;
    T h = (dnf <= T(1e-10) || dny <= T(1e-10)) ? T(1e-6) : sqrt(dny / dnf) * T(0.01);
    h = min(h, hmax);
    F y1 = f0, f1 = f0;
    for (std::size_t i = 0; i < size_of(f0); ++i)
        y1[i] = y0[static_cast<Eigen::Index>(i)] + (dir * h) * f0[i];
    eval_rhs(sys, t0 + dir * h, y1, f1, stats);
    T der2 = T(0);
    for (std::size_t i = 0; i < size_of(f0); ++i)
        der2 += ((f1[i] - f0[i]) * inv[i]) * ((f1[i] - f0[i]) * inv[i]);
    der2 = sqrt(der2 / n) / h;
    if (!(der2 == der2) || der2 > std::numeric_limits<T>::max()) return dir * h; // f1 not finite
    const T der12 = max(der2, sqrt(dnf));
    const T h1 =
        der12 <= T(1e-15) ? max(T(1e-6), h * T(1e-3)) : pow(T(0.01) / der12, T(1) / T(order));
    return dir * min(min(T(100) * h, h1), hmax);
}

} // namespace detail
} // namespace rotgen
