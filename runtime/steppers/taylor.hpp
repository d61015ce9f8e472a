/// \file
/// rotgen runtime — the Taylor method of variable order and step (Jorba & Zou, "A software package
/// for the numerical integration of ODEs by means of high-order Taylor methods", Exp. Math. 14
/// (2005) 99-117; heyoka, Biscani & Izzo, MNRAS 504 (2021) 2614-2628).
///
/// Each step expands the solution through (t, y) into its Taylor polynomial, from the system's
/// generated coefficient function (`rotgen emit --outputs taylor`; x^[k] = x^(k)/k!):
///   y(t + h) = sum_{k=0..p} y^[k] h^k          (Estrin's scheme to order 16, split Horner above)
/// The order and the step come from the tolerance and the last two coefficients (Jorba & Zou,
/// section 3.2, as heyoka applies it, with rotgen's rtol/atol):
///   control  relative (eps = rtol) when rtol ||y||_inf > atol, else absolute (eps = atol)
///   order    p = ceil(-ln(eps)/2 + 1)                     (JZ (3.12): the cost per unit time
///                                                           is smallest there)
///   radius   rho_k = (s / ||y^[k]||_inf)^(1/k), s = ||y||_inf (relative) or 1 (absolute),
///            rho = min(rho_{p-1}, rho_p)                   (an estimate of the radius of
///                                                           convergence from the series' tail)
///   step     h = rho / e^2 · exp(-0.7 / (p - 1))           (JZ (3.14): the truncation error
///                                                           ~ eps s, with a safety factor)
/// For a double the rule's logarithm and exponential are taken to about 1e-7, not to the last bit
/// (detail::ln_step, detail::exp_step: each step waits on them).
/// There is no error estimate and no rejected step: the step is chosen before it is taken (the
/// driver asks choose_step(), integrate/self_stepping.hpp). With `step > 0` the method takes fixed
/// steps of order `order` (or the order of the tolerance) instead. Dense output is the step's own
/// polynomial at theta h: free, and of the step's accuracy.
///
/// The system must provide, beyond the system concept (system.hpp),
///   std::size_t taylor_series() const;            coefficient series taylor() fills
///   void taylor(T t, T* c, int order) const;      the generated taylor(t, c, order, p)
/// (generated_taylor_system in taylor_system.hpp wraps a generated header). An expansion is
/// counted as one rhs evaluation in step_stats (its cost is about that of order/2 evaluations).
/// Stepper concept (stepper.hpp): nominal order 20, no error estimate, its own dense output, no
/// Jacobian, chooses_step.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../lanes.hpp"
#include "../step_control.hpp"
#include "../stepper.hpp"

namespace rotgen {

template <class T, class S> class taylor_stepper;
template <class T, class S> class taylor_lane_stepper; // taylor_lanes.hpp

namespace detail {
template <class S, class T, class = void> struct has_taylor : std::false_type {};
template <class S, class T>
struct has_taylor<
    S, T,
    std::void_t<decltype(std::declval<const S&>().taylor(std::declval<T>(), std::declval<T*>(), 1)),
                decltype(std::declval<const S&>().taylor_series())>> : std::true_type {};

/// x = 2^e m with m in [1, 2), for a normal double x > 0: m, and e into e (from the bits)
inline double significand(double x, int& e) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    e = static_cast<int>((bits >> 52) & 0x7ff) - 1023;
    bits = (bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL;
    double m;
    std::memcpy(&m, &bits, sizeof m);
    return m;
}

/// A lower bound of log2 x for a normal double x > 0, at most log2_width below it: the exponent
/// e plus m - 1 for the significand m in [1, 2) (log2 is concave, so above that chord, and at most
/// log2(1/ln 2) - (1/ln 2 - 1) = 0.0861 above it).
inline constexpr double log2_width = 0.0861;
inline double log2_below(double x) {
    int e;
    const double m = significand(x, e);
    return e + (m - 1);
}

/// e^x to a relative 1.7e-7, not to the last bit: 2^n 2^f with x log2(e) = n + f, n an integer,
/// |f| <= 1/2, 2^f by its Taylor polynomial of degree 6 in Estrin's form (largest relative error
/// 1.6e-7 over |f| <= 1/2), 2^n from its bits; libm's exp where 2^n would not be a normal double
/// or x is not a number. Jorba and Zou's step needs no more (its safety factor is a choice; the
/// step moves by 2e-7 at most, the count of steps not at all on the bench's scenes), and a step
/// waits on this (the next expansion needs it): glibc's exp took 4% more of the free top's step.
inline double exp_step(double x) {
    const double y = x * 1.4426950408889634; // log2(e)
    if (!(y > -1020.0 && y < 1020.0)) return std::exp(x);
    // 1.5 2^52: y + round rounds y to an integer (IEEE arithmetic: not under -ffast-math)
    constexpr double round = 6755399441055744.0;
    const double shifted = y + round;
    const double n = shifted - round;
    const double f = y - n, f2 = f * f, f4 = f2 * f2;
    constexpr double c1 = 0.6931471805599453, c2 = 0.2402265069591007, c3 = 0.055504108664821576,
                     c4 = 0.009618129107628477, c5 = 0.0013333558146428441,
                     c6 = 1.5403530393381606e-4; // (ln 2)^k / k!
    const double q = ((1.0 + c1 * f) + (c2 + c3 * f) * f2) + ((c4 + c5 * f) + c6 * f2) * f4;
    std::uint64_t bits;
    std::memcpy(&bits, &shifted, sizeof bits); // n in its low bits (two's complement)
    bits = (bits + 1023) << 52;
    double scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return q * scale;
}

/// ln x for a normal double x > 0 to 4e-8 (absolute), not to the last bit: (e + log2 m) ln 2 for
/// x = 2^e m, m in [1, 2), with log2 m by its polynomial of degree 8 in m - 3/2 through the
/// Chebyshev points of [1, 2] (largest error 5.6e-8 in log2 m). The step's size needs no more (its
/// h moves by a relative 1e-8 at most), and a step waits on this: glibc's log took 2.5% more of
/// the free top's step at orders 11 and 15.
inline double ln_step(double x) {
    int e;
    const double t = significand(x, e) - 1.5, t2 = t * t, t4 = t2 * t2;
    constexpr double c0 = 0.5849625007211562, c1 = 0.9617959853848302, c2 = -0.3205984711766454,
                     c3 = 0.14252592843166906, c4 = -0.07126680308997543, c5 = 0.037466490279291054,
                     c6 = -0.02079003319889751, c7 = 0.014770571157797108,
                     c8 = -0.008665699309098378;
    const double q = ((c0 + c1 * t) + (c2 + c3 * t) * t2) +
                     (((c4 + c5 * t) + (c6 + c7 * t) * t2) + c8 * t4) * t4;
    return (e + q) * 0.6931471805599453;
}

/// r_i = sum_{m=0..p-1} d(m, i) h^m for i < W, as E(h^2) + h O(h^2) with E the sum of the even m
/// and O of the odd: two independent chains of Horner's scheme at half the length, for each of the
/// W sums side by side (held in registers, the loop over i inside the loop over m): for the orders
/// above estrin()'s.
template <std::size_t W, class T, class D>
ROTGEN_ALWAYS_INLINE void split_horner(int p, T h, const D& d, T* r) {
    const T u = h * h;
    const int top = p - 1;                          // >= 1: the order is at least 2
    int me = top - top % 2, mo = top - 1 + top % 2; // the highest even and odd m
    T e[W], o[W];
    for (std::size_t i = 0; i < W; ++i)
        e[i] = d(me, i), o[i] = d(mo, i);
    for (me -= 2, mo -= 2; mo >= 1; me -= 2, mo -= 2)
        for (std::size_t i = 0; i < W; ++i) {
            e[i] = e[i] * u + d(me, i);
            o[i] = o[i] * u + d(mo, i);
        }
    if (me >= 0)
        for (std::size_t i = 0; i < W; ++i)
            e[i] = e[i] * u + d(me, i);
    for (std::size_t i = 0; i < W; ++i)
        r[i] = e[i] + h * o[i];
}

/// sum_{m=Lo..Lo+N-1} d(m, i) h^(m-Lo) by Estrin's scheme: the lower half plus the upper half
/// times h^half, half the largest power of two below N, and hp[j] = h^(2^j).
template <int Lo, int N, class T, class D>
ROTGEN_ALWAYS_INLINE T estrin_sum(const T* hp, const D& d, std::size_t i) {
    if constexpr (N == 1) {
        return d(Lo, i);
    } else {
        constexpr int j = [] { // half = 2^j
            int k = 0;
            while ((2 << k) < N)
                ++k;
            return k;
        }();
        constexpr int half = 1 << j;
        return estrin_sum<Lo, half>(hp, d, i) + estrin_sum<Lo + half, N - half>(hp, d, i) * hp[j];
    }
}

/// r_i = sum_{m=0..P-1} d(m, i) h^m for i < W with the order P a constant, by Estrin's scheme: a
/// tree of depth log2(P) where Horner's is a chain of P - 1 products and sums. A step waits on
/// these sums (the next expansion needs them): split_horner's two chains took 3% more of the free
/// top's step at orders 11 and 15.
template <int P, std::size_t W, class T, class D>
ROTGEN_ALWAYS_INLINE void estrin(T h, const D& d, T* r) {
    T hp[5] = {h};
    for (int j = 1; j < 5; ++j)
        hp[j] = hp[j - 1] * hp[j - 1];
    for (std::size_t i = 0; i < W; ++i)
        r[i] = estrin_sum<0, P>(hp, d, i);
}

/// The orders estrin() sums: 2 .. 16, those of the tolerances down to 1e-13 (order_for), where the
/// truncation error is the larger. Above, where the roundings are, split_horner's sums round less
/// (over random series at most 2.3 units of the last place of sum |d(m)| h^m, Estrin's 3.8; the
/// free top's error at tol 1e-15 over 400 initial states, median and 90th percentile: 1.5e-15 and
/// 4.0e-15 with split_horner, 1.9e-15 and 4.6e-15 with Estrin).
inline constexpr int estrin_orders = 15; // the orders 2 .. 16
template <std::size_t W, class T, class D, int... Q>
ROTGEN_ALWAYS_INLINE bool estrin_of_order(int p, T h, const D& d, T* r,
                                          std::integer_sequence<int, Q...>) {
    return ((p == Q + 2 && (estrin<Q + 2, W>(h, d, r), true)) || ...);
}

/// r_i = sum_{m=0..p-1} d(m, i) h^m for i < W: estrin() for its orders, else split_horner (the
/// same bits for any W: each sum is on its own).
template <std::size_t W, class T, class D>
ROTGEN_ALWAYS_INLINE void series_sum(int p, T h, const D& d, T* r) {
    if (!estrin_of_order<W>(p, h, d, r, std::make_integer_sequence<int, estrin_orders>{}))
        split_horner<W>(p, h, d, r);
}

/// The coefficients series_sums reads: d(m, i) = c[m dm + i di] (the sum i's coefficient m). A
/// view, not a lambda: at the sums' size GCC stopped inlining an accessor lambda in rotgen's own
/// build (a call per coefficient: a sweep's members took 18% longer).
template <class T> struct series_view {
    const T* c;
    std::size_t dm, di;
    ROTGEN_ALWAYS_INLINE T operator()(int m, std::size_t i) const {
        return c[static_cast<std::size_t>(m) * dm + i * di];
    }
    series_view from(std::size_t i0) const { return {c + i0 * di, dm, di}; }
};

/// series_sum over n sums: W = n when n is a small constant, else blocks of 4 and single ones.
template <int N, class T>
ROTGEN_ALWAYS_INLINE void series_sums(int p, T h, std::size_t n, const series_view<T>& d, T* r) {
    if constexpr (N > 0 && N <= 8) {
        series_sum<std::size_t(N)>(p, h, d, r);
    } else {
        std::size_t i0 = 0;
        for (; i0 + 4 <= n; i0 += 4)
            series_sum<4>(p, h, d.from(i0), r + i0);
        for (; i0 < n; ++i0)
            series_sum<1>(p, h, d.from(i0), r + i0);
    }
}
} // namespace detail

/// True when the system gives its Taylor coefficients (the taylor method can integrate it).
template <class S, class T> inline constexpr bool has_taylor_v = detail::has_taylor<S, T>::value;

/// Options of the Taylor method of variable order and step (Jorba & Zou; the file's comment):
/// tolerances, an optional fixed step, order and largest step, and a step budget. Integrates
/// systems that give their Taylor coefficients (has_taylor_v; taylor_system.hpp, lanes.hpp).
template <class T> struct taylor {
    /// The floating-point type of the run.
    using scalar = T;
    /// Marks a method the driver accepts (stepper.hpp).
    static constexpr bool is_rotgen_method = true;
    static constexpr bool adaptive = false; ///< no error estimate: the step is chosen, not checked
    /// Chooses its own step (choose_step(); integrate/self_stepping.hpp).
    static constexpr bool chooses_step = true;
    template <class S>
    static constexpr bool supports =
        has_taylor_v<S, T>; ///< true for a system it can integrate: one with Taylor coefficients
    /// a lane system (lanes.hpp) expands its lanes together and takes their smallest step
    template <class S>
    using stepper = std::conditional_t<detail::is_lane_system_v<S>, taylor_lane_stepper<T, S>,
                                       taylor_stepper<T, S>>;

    T rtol = T(1e-10);               ///< relative tolerance (eps of the relative control)
    T atol = T(1e-10);               ///< absolute tolerance (eps of the absolute control)
    T step = T(0);                   ///< > 0: fixed steps of this size, no step-size choice
    T hmax = T(0);                   ///< largest step; 0: |t_end - t0|
    int order = 0;                   ///< 0: from the tolerance, per step; > 0: always this order
    std::size_t max_steps = 1000000; ///< step budget
    /// What the tolerance is relative to (step_control.hpp): with groups, the weighted control
    /// (the file's comment); without, Jorba and Zou's relative or absolute control.
    error_layout layout;
    T calibration_scale =
        T(1); ///< the weighted control holds the truncation to F sk_i (F: step_control.hpp)
    T calibration_power = T(0); ///< see calibration_scale
    /// calibrate()'s values for scenes (bench/proportionality: rtol means the error at the samples)
    static constexpr double calibrated_scale = 10;
    static constexpr double calibrated_power = 0; ///< see calibrated_scale

    /// The method's name, as scene files and `rotgen simulate` spell it.
    std::string name() const { return "taylor"; }
    /// An empty string when the options are valid, else the reason (one line).
    std::string check() const {
        using std::isfinite;
        const T eps = std::numeric_limits<T>::epsilon();
        if (!(step >= T(0)) || !isfinite(step)) return "step must be finite and >= 0";
        if (order < 0 || order > 60) return "order must lie in 1..60 (0: from the tolerance)";
        if (!(rtol >= T(0)) || !(atol >= T(0)) || !isfinite(rtol) || !isfinite(atol))
            return "tolerances must be finite and >= 0";
        if (rtol == T(0) && atol == T(0)) return "rtol and atol are both 0";
        if ((rtol != T(0) && rtol < eps) || (atol != T(0) && atol < eps * eps))
            return "a tolerance is below the precision of the scalar type";
        if (!(hmax >= T(0))) return "hmax must be >= 0";
        return "";
    }

    /// Jorba & Zou (3.12): the order for the tolerance eps.
    static int order_for(T eps) {
        using std::ceil;
        using std::log;
        return std::max(2, static_cast<int>(ceil(-log(eps) / T(2) + T(1))));
    }

    /// The order of a step under the relative control (rtol's) or the absolute one (atol's).
    int order_of(bool relative) const {
        return order > 0 ? order : order_for(relative ? rtol : atol);
    }

    /// Jorba & Zou's step at order p from the norms of its last two coefficients, with what
    /// depends on p alone computed once: h = exp(c - m), m = max over k = p - 1, p of
    /// ln(||y^[k]|| / s) / k (-inf when both norms are 0: the series ends) and
    /// c = -2 - 0.7 / (p - 1). The step waits on this chain (the next expansion needs the step),
    /// so it holds no division: the reciprocals of k and of s are taken off the chain.
    struct step_rule {
        int p = 2;        ///< the order p
        T inv_p1 = T(1);  ///< 1/(p − 1)
        T inv_p = T(0.5); ///< 1/p
        T c = T(-2.7);    ///< −2 − 0.7/(p − 1)
        /// The rule for order `order` (>= 2).
        explicit step_rule(int order = 2)
            : p(order), inv_p1(T(1) / T(order - 1)), inv_p(T(1) / T(order)),
              c(-T(2) - T(0.7) / T(order - 1)) {}
        /// The weighted control's rule: h = rho · eps^(1/p) · exp(-0.7 / (p - 1)), so that the
        /// truncation error is eps relative to the weights whatever p's rounding up (JZ's e^-2 is
        /// eps^(1/p) at p = -ln(eps)/2 exactly, and up to e^2 looser at p rounded up).
        step_rule(int order, T ln_eps) : step_rule(order) {
            c = ln_eps * inv_p - T(0.7) / T(order - 1);
        }

        /// m from the norms n1 = ||y^[p-1]||, n = ||y^[p]|| and inv_s = 1 / s, s = ||y||_inf
        /// (relative) or 1 (absolute): one logarithm where the quotients n / s are normal numbers
        T ln_inverse_radius(T n1, T n, T s, T inv_s) const {
            using std::log;
            const T a = n1 * inv_s, b = n * inv_s;
            if (std::isnormal(a) && std::isnormal(b)) return max_ln_ratio(a, b);
            const T minus_inf = -std::numeric_limits<T>::infinity();
            const auto ln_ratio = [&](T nk, T inv_k, T q) {
                if (!(nk > T(0))) return minus_inf;
                return (std::isnormal(q) ? ln(q) : log(nk) - log(s)) * inv_k;
            };
            return std::max(ln_ratio(n1, inv_p1, a), ln_ratio(n, inv_p, b));
        }

        /// max(ln(a) / (p - 1), ln(b) / p) for normal a, b > 0, with one logarithm where bounds on
        /// log2 from the bits of the two doubles already tell which is larger (else two): the same
        /// bits either way (the margin, 1e-3, covers ln's error, 4e-8, many times over).
        T max_ln_ratio(T a, T b) const {
            if constexpr (std::is_same_v<T, double>) {
                constexpr double w = detail::log2_width + 1e-3;
                const double la = detail::log2_below(a), lb = detail::log2_below(b);
                const int j = p - 1, k = p;
                // la / j > (lb + w) / k, multiplied out
                if (la * k > (lb + w) * j) return ln(a) * inv_p1;
                if (lb * j > (la + w) * k) return ln(b) * inv_p;
            }
            return std::max(ln(a) * inv_p1, ln(b) * inv_p);
        }

        /// the logarithm of a normal number > 0: for a double detail::ln_step
        static T ln(T x) {
            using std::log;
            if constexpr (std::is_same_v<T, double>)
                return detail::ln_step(x);
            else
                return log(x);
        }

        /// the step for m (+inf when m is -inf): exp(c - m), for a double by detail::exp_step
        T step(T m) const {
            using std::exp;
            if constexpr (std::is_same_v<T, double>)
                return detail::exp_step(c - m);
            else
                return exp(c - m);
        }

        /// The step under the error per unit step (error_layout::span, ln_span its logarithm):
        /// the truncation held to the share h / span of the tolerance, (h/rho)^p ∝ eps h / span,
        /// is ln h = (c - m) + (c - m - ln_span) / (p - 1), the rule's step where that is longer
        /// than the span. m finite.
        T step_per_unit(T m, T ln_span) const {
            using std::min;
            return step(m - min(T(0), (c - m - ln_span) * inv_p1));
        }
    };

    /// The highest order a step may take: `order` if fixed, else the larger of the tolerances'.
    int max_order() const {
        return order > 0
                   ? order
                   : std::max(rtol > T(0) ? order_for(rtol) : 2, atol > T(0) ? order_for(atol) : 2);
    }
};

/// The Taylor method's working storage for one system type S (the stepper concept of
/// stepper.hpp, with choose_step()): the expansion at each step's start, its order and step from
/// the tolerance, and the polynomial as the dense output.
template <class T, class S> class taylor_stepper {
  public:
    /// The floating-point type of the run.
    using scalar = T;
    /// The system type S this stepper integrates.
    using system_type = S;
    /// The state vector of S.
    using vector = state_vector<T, S>;
    /// What attempt() returns.
    using outcome = step_outcome<T>;

    static constexpr int order = 20; ///< nominal: the order of each step follows the tolerance
    /// No error estimate: attempt() returns err = 0.
    static constexpr bool error_estimate = false;
    /// Samples inside a step come from the stepper's own interpolant, dense().
    static constexpr dense_kind dense_output = dense_kind::continuous_extension;
    /// Order of the interpolant (local error O(h^(dense_order+1))).
    static constexpr int dense_order = 20;
    /// Never evaluates ∂f/∂y.
    static constexpr bool uses_jacobian = false;
    /// Chooses its own step (choose_step(); integrate/self_stepping.hpp).
    static constexpr bool chooses_step = true;

    /// Storage for n state components, with the options of m.
    taylor_stepper(const taylor<T>& m, std::size_t n)
        : m_method(m), m_n(n), m_y1(vector::Zero(static_cast<Eigen::Index>(n))), m_f0(m_y1),
          m_comp(m_y1), m_comp_start(m_y1), m_tail(m_y1),
          m_weight(vector::Ones(static_cast<Eigen::Index>(n))),
          m_weighted(m.layout.groups.size() == n) {
        m_max_order = m.max_order();
        m_order_abs = m.order_of(false), m_order_rel = m.order_of(true);
        m_rule_abs = rule(m_order_abs), m_rule_rel = rule(m_order_rel);
        if (m_weighted) {
            using std::log;
            const T f =
                calibration_factor(m.calibration_scale, m.calibration_power, m.rtol, m.atol);
            if (m.rtol > T(0)) m_rule_rel = rule(m_order_rel, log(f * m.rtol));
            if (m.atol > T(0)) m_rule_abs = rule(m_order_abs, log(f * m.atol));
            m_per_unit = m.layout.span > 0;
            if (m_per_unit) m_ln_span = log(T(m.layout.span));
        }
    }

    /// Begins a run at (t0, y0): evaluates f(t0, y0); false when it is not finite.
    bool start(const S& sys, T t0, const vector& y0, step_stats& stats) {
        if constexpr (has_taylor_v<S, T>) {
            m_c.assign(sys.taylor_series() * static_cast<std::size_t>(m_max_order + 1), T(0));
            expand(sys, t0, y0, stats);
            for (std::size_t i = 0; i < size(); ++i)
                m_f0[static_cast<Eigen::Index>(i)] = coefficient(i, 1);
            return m_f0.allFinite();
        } else {
            (void)sys, (void)t0, (void)y0, (void)stats;
            return false;
        }
    }
    /// f(t0, y0), after start() (for the initial step selection).
    const vector& f_start() const { return m_f0; }

    /// The step the tolerance allows from (t, y) (> 0; +inf when the series ends; NaN when the
    /// coefficients are not finite). Expands the solution there; attempt() uses the expansion.
    T choose_step(const S& sys, T t, const vector& y, step_stats& stats) {
        if (!m_expanded) expand(sys, t, y, stats);
        const int p = m_p;
        const T np1 = norm(p - 1), np = norm(p);
        if (!(np1 == np1) || !(np == np)) return std::numeric_limits<T>::quiet_NaN();
        // in logarithms, then one exp (two pow calls and an exp cost about a fifth of a step at
        // order 15)
        const auto& sr = m_relative ? m_rule_rel : m_rule_abs;
        const T m = sr.ln_inverse_radius(np1, np, m_relative ? m_norm0 : T(1), m_inv_s);
        if (m == -std::numeric_limits<T>::infinity()) return -m;
        return m_per_unit ? sr.step_per_unit(m, m_ln_span) : sr.step(m);
    }

    /// y + sum_{k>=1} y^[k] h^k: the increment added with Kahan's compensation carried from step
    /// to step (m_comp: what the last addition rounded away, negated) while the run continues
    /// from the state this stepper returned, so that the state's rounding does not accumulate.
    outcome attempt(const S& sys, T t, const vector& y, T h, step_stats& stats, bool) {
        if (!m_expanded) expand(sys, t, y, stats);
        m_h = h;
        const bool continued = m_stepped && y == m_y1;
        tails(h, m_tail);
        for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(size()); ++i) {
            m_comp_start[i] = continued ? m_comp[i] : T(0);
            const T increment = h * m_tail[i] - m_comp_start[i];
            m_y1[i] = y[i] + increment;
            m_comp[i] = (m_y1[i] - y[i]) - increment;
        }
        m_stepped = true;
        return {m_y1.allFinite() ? status::ok : status::non_finite, T(0)};
    }

    /// The next step expands anew; the coefficients stay for dense(). Always true.
    bool accept(const S&, step_stats&, bool) {
        m_expanded = false; // the coefficients stay for dense(): the next step expands anew
        return true;
    }

    /// The state at t + h of the last attempt().
    const vector& y_new() const { return m_y1; }

    /// The step's polynomial at theta h (from the step's start, compensated as the step's end).
    void dense(T theta, vector& out) const {
        const T th = theta * m_h;
        tails(th, out);
        for (std::size_t i = 0; i < size(); ++i) {
            const auto e = static_cast<Eigen::Index>(i);
            out[e] = coefficient(i, 0) + (th * out[e] - m_comp_start[e]);
        }
    }

    int last_order() const { return m_p; } ///< the order of the last expansion

  private:
    /// The state's size: a compile-time constant where the system's is (the loops over the
    /// components unroll: 8% of a step of the free top at order 11), else the run's.
    static constexpr Eigen::Index fixed_size = vector::RowsAtCompileTime;
    std::size_t size() const { return fixed_size > 0 ? std::size_t(fixed_size) : m_n; }

    T coefficient(std::size_t i, int k) const {
        return m_c[i * static_cast<std::size_t>(m_p + 1) + static_cast<std::size_t>(k)];
    }

    /// max_i w_i |y_i^[k]| (w_i = 1 but under a layout: expand())
    T norm(int k) const {
        using std::abs;
        using std::max;
        T r = T(0);
        for (std::size_t i = 0; i < size(); ++i) {
            const T v = abs(coefficient(i, k)) * m_weight[static_cast<Eigen::Index>(i)];
            if (!(v == v)) return v;
            r = max(r, v);
        }
        return r;
    }

    /// r_i = sum_{k=1..p} y_i^[k] h^(k-1) for every component i (detail::series_sum, the
    /// components side by side).
    template <class V> void tails(T h, V& r) const {
        const auto stride = static_cast<std::size_t>(m_p + 1);
        detail::series_sums<V::RowsAtCompileTime>(m_p, h, static_cast<std::size_t>(r.size()),
                                                  {m_c.data() + 1, 1, stride}, &r[0]);
    }

    /// The control and order at (t, y), then the coefficients up to that order.
    void expand(const S& sys, T t, const vector& y, step_stats& stats) {
        using std::abs;
        using std::max;
        m_norm0 = T(0);
        for (std::size_t i = 0; i < size(); ++i)
            m_norm0 = max(m_norm0, abs(y[static_cast<Eigen::Index>(i)]));
        const taylor<T>& m = m_method;
        m_relative = m.rtol > T(0) && m.rtol * m_norm0 > m.atol;
        m_inv_s = m_relative ? T(1) / m_norm0 : T(1); // off the step's chain: see step_rule
        if (m_weighted) weigh(y);
        m_p = m_relative ? m_order_rel : m_order_abs;
        const std::size_t stride = static_cast<std::size_t>(m_p + 1);
        for (std::size_t i = 0; i < size(); ++i)
            m_c[i * stride] = y[static_cast<Eigen::Index>(i)];
        sys.taylor(t, m_c.data(), m_p);
        ++stats.rhs_evals;
        m_expanded = true;
    }

    /// The weighted control (a layout with groups): w_i = eps / sk_i at the step's start, eps =
    /// rtol (or atol when rtol is 0) choosing the order, s = 1: the truncation error of component
    /// i is held near sk_i = atol + rtol m_i (error_layout), as every method's error is.
    void weigh(const vector& y) {
        const taylor<T>& m = m_method;
        detail::inverse_scales(m.layout, y, y, m.atol, m.rtol, 1, m_weight);
        m_relative = m.rtol > T(0);
        m_weight *= m_relative ? m.rtol : m.atol;
        m_norm0 = T(1), m_inv_s = T(1);
    }

    taylor<T> m_method;
    std::size_t m_n;
    int m_max_order = 2, m_p = 2;
    int m_order_abs = 2, m_order_rel = 2; ///< the order of each control (order_of: one log each)
    using rule = typename taylor<T>::step_rule;
    rule m_rule_abs, m_rule_rel; ///< the step rule of each control's order
    bool m_expanded = false, m_relative = false;
    T m_norm0 = T(0), m_inv_s = T(1), m_h = T(0);
    std::vector<T> m_c; ///< series s, coefficient k at s * (m_p + 1) + k
    vector m_y1, m_f0;
    vector m_comp, m_comp_start; ///< Kahan's compensation of m_y1, and of the step's start
    vector m_tail;               ///< tails(): the step's sum of y^[k] h^(k-1), k >= 1
    vector m_weight;             ///< w_i of norm(): 1, or eps / sk_i under a layout (weigh())
    bool m_weighted;             ///< the layout has groups: the weighted control
    bool m_per_unit = false;     ///< the weighted control per unit step (error_layout::span)
    T m_ln_span = T(0);          ///< ln of error_layout::span when m_per_unit
    bool m_stepped = false;      ///< m_y1 and m_comp hold a step's end
};

} // namespace rotgen

#include "taylor_lanes.hpp"

namespace rotgen {
static_assert(check_method<taylor<double>>());
} // namespace rotgen
