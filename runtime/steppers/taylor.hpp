// rotgen runtime — the Taylor method of variable order and step (Jorba & Zou, "A software package
// for the numerical integration of ODEs by means of high-order Taylor methods", Exp. Math. 14
// (2005) 99-117; heyoka, Biscani & Izzo, MNRAS 504 (2021) 2614-2628).
//
// Each step expands the solution through (t, y) into its Taylor polynomial, from the system's
// generated coefficient function (`rotgen emit --outputs taylor`; x^[k] = x^(k)/k!):
//   y(t + h) = sum_{k=0..p} y^[k] h^k                                 (Horner's scheme)
// The order and the step come from the tolerance and the last two coefficients (Jorba & Zou,
// section 3.2, as heyoka applies it, with rotgen's rtol/atol):
//   control  relative (eps = rtol) when rtol ||y||_inf > atol, else absolute (eps = atol)
//   order    p = ceil(-ln(eps)/2 + 1)                     (JZ (3.12): the cost per unit time
//                                                           is smallest there)
//   radius   rho_k = (s / ||y^[k]||_inf)^(1/k), s = ||y||_inf (relative) or 1 (absolute),
//            rho = min(rho_{p-1}, rho_p)                   (an estimate of the radius of
//                                                           convergence from the series' tail)
//   step     h = rho / e^2 · exp(-0.7 / (p - 1))           (JZ (3.14): the truncation error
//                                                           ~ eps s, with a safety factor)
// There is no error estimate and no rejected step: the step is chosen before it is taken (the
// driver asks choose_step(), integrate/self_stepping.hpp). With `step > 0` the method takes fixed
// steps of order `order` (or the order of the tolerance) instead. Dense output is the step's own
// polynomial at theta h: free, and of the step's accuracy.
//
// The system must provide, beyond the system concept (system.hpp),
//   std::size_t taylor_series() const;            coefficient series taylor() fills
//   void taylor(T t, T* c, int order) const;      the generated taylor(t, c, order, p)
// (generated_taylor_system in taylor_system.hpp wraps a generated header). An expansion is
// counted as one rhs evaluation in step_stats (its cost is about that of order/2 evaluations).
// Stepper concept (stepper.hpp): nominal order 20, no error estimate, its own dense output, no
// Jacobian, chooses_step.
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

// A lower bound of log2 x for a normal double x > 0, at most log2_width below it: the exponent
// e plus m - 1 for the significand m in [1, 2) (log2 is concave, so above that chord, and at most
// log2(1/ln 2) - (1/ln 2 - 1) = 0.0861 above it).
inline constexpr double log2_width = 0.0861;
inline double log2_below(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    const int e = static_cast<int>((bits >> 52) & 0x7ff) - 1023;
    bits = (bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL;
    double m;
    std::memcpy(&m, &bits, sizeof m);
    return e + (m - 1);
}

// r_i = sum_{m=0..p-1} d(m, i) h^m for i < W, as E(h^2) + h O(h^2) with E the sum of the even m
// and O of the odd: two independent chains of Horner's scheme at half the length, for each of the
// W sums side by side (held in registers, the loop over i inside the loop over m). A step waits
// on these chains (the next expansion needs their sums): one Horner chain over m after another
// was 8% of the free top's time.
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

// split_horner over n sums: W = n when n is a small constant, else blocks of 4 and single ones.
template <int N, class T, class D>
ROTGEN_ALWAYS_INLINE void split_horners(int p, T h, std::size_t n, const D& d, T* r) {
    if constexpr (N > 0 && N <= 8) {
        split_horner<std::size_t(N)>(p, h, d, r);
    } else {
        std::size_t i0 = 0;
        const auto shifted = [&](int m, std::size_t i) { return d(m, i0 + i); };
        for (; i0 + 4 <= n; i0 += 4)
            split_horner<4>(p, h, shifted, r + i0);
        for (; i0 < n; ++i0)
            split_horner<1>(p, h, shifted, r + i0);
    }
}
} // namespace detail

// True when the system gives its Taylor coefficients (the taylor method can integrate it).
template <class S, class T> inline constexpr bool has_taylor_v = detail::has_taylor<S, T>::value;

template <class T> struct taylor {
    using scalar = T;
    static constexpr bool is_rotgen_method = true;
    static constexpr bool adaptive = false; // no error estimate: the step is chosen, not checked
    static constexpr bool chooses_step = true;
    template <class S> static constexpr bool supports = has_taylor_v<S, T>;
    // a lane system (lanes.hpp) expands its lanes together and takes their smallest step
    template <class S>
    using stepper = std::conditional_t<detail::is_lane_system_v<S>, taylor_lane_stepper<T, S>,
                                       taylor_stepper<T, S>>;

    T rtol = T(1e-10); // relative tolerance (eps of the relative control)
    T atol = T(1e-10); // absolute tolerance (eps of the absolute control)
    T step = T(0);     // > 0: fixed steps of this size, no step-size choice
    T hmax = T(0);     // largest step; 0: |t_end - t0|
    int order = 0;     // 0: from the tolerance, per step; > 0: always this order
    std::size_t max_steps = 1000000;

    std::string name() const { return "taylor"; }
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

    // Jorba & Zou (3.12): the order for the tolerance eps.
    static int order_for(T eps) {
        using std::ceil;
        using std::log;
        return std::max(2, static_cast<int>(ceil(-log(eps) / T(2) + T(1))));
    }

    // The order of a step under the relative control (rtol's) or the absolute one (atol's).
    int order_of(bool relative) const {
        return order > 0 ? order : order_for(relative ? rtol : atol);
    }

    // Jorba & Zou's step at order p from the norms of its last two coefficients, with what
    // depends on p alone computed once: h = exp(c - m), m = max over k = p - 1, p of
    // ln(||y^[k]|| / s) / k (-inf when both norms are 0: the series ends) and
    // c = -2 - 0.7 / (p - 1). The step waits on this chain (the next expansion needs the step),
    // so it holds no division: the reciprocals of k and of s are taken off the chain.
    struct step_rule {
        int p = 2;
        T inv_p1 = T(1), inv_p = T(0.5), c = T(-2.7);
        explicit step_rule(int order = 2)
            : p(order), inv_p1(T(1) / T(order - 1)), inv_p(T(1) / T(order)),
              c(-T(2) - T(0.7) / T(order - 1)) {}

        // m from the norms n1 = ||y^[p-1]||, n = ||y^[p]|| and inv_s = 1 / s, s = ||y||_inf
        // (relative) or 1 (absolute): one logarithm where the quotients n / s are normal numbers
        T ln_inverse_radius(T n1, T n, T s, T inv_s) const {
            using std::log;
            const T a = n1 * inv_s, b = n * inv_s;
            if (std::isnormal(a) && std::isnormal(b)) return max_ln_ratio(a, b);
            const T minus_inf = -std::numeric_limits<T>::infinity();
            const auto ln_ratio = [&](T nk, T inv_k, T q) {
                if (!(nk > T(0))) return minus_inf;
                return (std::isnormal(q) ? log(q) : log(nk) - log(s)) * inv_k;
            };
            return std::max(ln_ratio(n1, inv_p1, a), ln_ratio(n, inv_p, b));
        }

        // max(ln(a) / (p - 1), ln(b) / p) for normal a, b > 0, with one logarithm where bounds on
        // log2 from the bits of the two doubles already tell which is larger (else two): the same
        // bits either way (the margin covers the logarithm's rounding many times over).
        T max_ln_ratio(T a, T b) const {
            using std::log;
            if constexpr (std::is_same_v<T, double>) {
                constexpr double w = detail::log2_width + 1e-3;
                const double la = detail::log2_below(a), lb = detail::log2_below(b);
                const int j = p - 1, k = p;
                // la / j > (lb + w) / k, multiplied out
                if (la * k > (lb + w) * j) return log(a) * inv_p1;
                if (lb * j > (la + w) * k) return log(b) * inv_p;
            }
            return std::max(log(a) * inv_p1, log(b) * inv_p);
        }

        // the step for m (+inf when m is -inf)
        T step(T m) const {
            using std::exp;
            return exp(c - m);
        }
    };

    // The highest order a step may take: `order` if fixed, else the larger of the tolerances'.
    int max_order() const {
        return order > 0
                   ? order
                   : std::max(rtol > T(0) ? order_for(rtol) : 2, atol > T(0) ? order_for(atol) : 2);
    }
};

template <class T, class S> class taylor_stepper {
  public:
    using scalar = T;
    using system_type = S;
    using vector = state_vector<T, S>;
    using outcome = step_outcome<T>;

    static constexpr int order = 20; // nominal: the order of each step follows the tolerance
    static constexpr bool error_estimate = false;
    static constexpr dense_kind dense_output = dense_kind::continuous_extension;
    static constexpr int dense_order = 20;
    static constexpr bool uses_jacobian = false;
    static constexpr bool chooses_step = true;

    taylor_stepper(const taylor<T>& m, std::size_t n)
        : m_method(m), m_n(n), m_y1(vector::Zero(static_cast<Eigen::Index>(n))), m_f0(m_y1),
          m_comp(m_y1), m_comp_start(m_y1), m_tail(m_y1) {
        m_max_order = m.max_order();
        m_order_abs = m.order_of(false), m_order_rel = m.order_of(true);
        m_rule_abs = rule(m_order_abs), m_rule_rel = rule(m_order_rel);
    }

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
    const vector& f_start() const { return m_f0; }

    // The step the tolerance allows from (t, y) (> 0; +inf when the series ends; NaN when the
    // coefficients are not finite). Expands the solution there; attempt() uses the expansion.
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
        return sr.step(m);
    }

    // y + sum_{k>=1} y^[k] h^k: the increment added with Kahan's compensation carried from step
    // to step (m_comp: what the last addition rounded away, negated) while the run continues
    // from the state this stepper returned, so that the state's rounding does not accumulate.
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

    bool accept(const S&, step_stats&, bool) {
        m_expanded = false; // the coefficients stay for dense(): the next step expands anew
        return true;
    }

    const vector& y_new() const { return m_y1; }

    // The step's polynomial at theta h (from the step's start, compensated as the step's end).
    void dense(T theta, vector& out) const {
        const T th = theta * m_h;
        tails(th, out);
        for (std::size_t i = 0; i < size(); ++i) {
            const auto e = static_cast<Eigen::Index>(i);
            out[e] = coefficient(i, 0) + (th * out[e] - m_comp_start[e]);
        }
    }

    int last_order() const { return m_p; } // the order of the last expansion

  private:
    // The state's size: a compile-time constant where the system's is (the loops over the
    // components unroll: 8% of a step of the free top at order 11), else the run's.
    static constexpr Eigen::Index fixed_size = vector::RowsAtCompileTime;
    std::size_t size() const { return fixed_size > 0 ? std::size_t(fixed_size) : m_n; }

    T coefficient(std::size_t i, int k) const {
        return m_c[i * static_cast<std::size_t>(m_p + 1) + static_cast<std::size_t>(k)];
    }

    // max_i |y_i^[k]|
    T norm(int k) const {
        using std::abs;
        using std::max;
        T r = T(0);
        for (std::size_t i = 0; i < size(); ++i) {
            const T v = abs(coefficient(i, k));
            if (!(v == v)) return v;
            r = max(r, v);
        }
        return r;
    }

    // r_i = sum_{k=1..p} y_i^[k] h^(k-1) for every component i (detail::split_horner, the
    // components side by side).
    template <class V> void tails(T h, V& r) const {
        const auto stride = static_cast<std::size_t>(m_p + 1);
        const T* c = m_c.data();
        detail::split_horners<V::RowsAtCompileTime>(
            m_p, h, static_cast<std::size_t>(r.size()),
            [&](int m, std::size_t i) { return c[i * stride + std::size_t(m + 1)]; }, &r[0]);
    }

    // The control and order at (t, y), then the coefficients up to that order.
    void expand(const S& sys, T t, const vector& y, step_stats& stats) {
        using std::abs;
        using std::max;
        m_norm0 = T(0);
        for (std::size_t i = 0; i < size(); ++i)
            m_norm0 = max(m_norm0, abs(y[static_cast<Eigen::Index>(i)]));
        const taylor<T>& m = m_method;
        m_relative = m.rtol > T(0) && m.rtol * m_norm0 > m.atol;
        m_inv_s = m_relative ? T(1) / m_norm0 : T(1); // off the step's chain: see step_rule
        m_p = m_relative ? m_order_rel : m_order_abs;
        const std::size_t stride = static_cast<std::size_t>(m_p + 1);
        for (std::size_t i = 0; i < size(); ++i)
            m_c[i * stride] = y[static_cast<Eigen::Index>(i)];
        sys.taylor(t, m_c.data(), m_p);
        ++stats.rhs_evals;
        m_expanded = true;
    }

    taylor<T> m_method;
    std::size_t m_n;
    int m_max_order = 2, m_p = 2;
    int m_order_abs = 2, m_order_rel = 2; // the order of each control (order_of: one log each)
    using rule = typename taylor<T>::step_rule;
    rule m_rule_abs, m_rule_rel; // the step rule of each control's order
    bool m_expanded = false, m_relative = false;
    T m_norm0 = T(0), m_inv_s = T(1), m_h = T(0);
    std::vector<T> m_c; // series s, coefficient k at s * (m_p + 1) + k
    vector m_y1, m_f0;
    vector m_comp, m_comp_start; // Kahan's compensation of m_y1, and of the step's start
    vector m_tail;               // tails(): the step's sum of y^[k] h^(k-1), k >= 1
    bool m_stepped = false;      // m_y1 and m_comp hold a step's end
};

} // namespace rotgen

#include "taylor_lanes.hpp"

namespace rotgen {
static_assert(check_method<taylor<double>>());
} // namespace rotgen
