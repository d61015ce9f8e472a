/// \file
/// rotgen runtime — the Taylor method in lanes (lanes.hpp): W members expanded together by one
/// batch call of their coefficient function, advanced by one shared step. Included by taylor.hpp,
/// whose method picks this stepper for a lane system with Taylor coefficients
/// (lane_taylor_system, lanes.hpp).
///
/// Coefficient k of component i of lane l is c[(i (p + 1) + k) W + l]: the scalar layout of
/// taylor.hpp with every coefficient widened to the W lanes, so that each loop below runs over the
/// lanes innermost (contiguous, vectorised).
///   control  per lane, as taylor.hpp: relative when rtol ||y_l||_inf > atol, else absolute
///   order    one for all lanes: the largest of the live lanes' orders (equal when they share
///            the control; JZ (3.12))
///   step     the smallest of the live lanes' Jorba–Zou steps at that order (taylor.hpp's rule on
///            each lane's own coefficients), so that every lane meets the tolerance: a lane's step
///            is never longer than its scalar run's would be from the same state
/// Stopped and failed lanes (lanes.hpp) take no part: the system zeroes their coefficients beyond
/// order 0, so that they stay where they are, and they choose neither the order nor the step.
/// One expansion of all lanes counts as one rhs evaluation, as a scalar expansion does.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

namespace rotgen {

namespace detail {
/// f(w) with the lane count as a compile-time constant where it is 4 or 8 (a whole number of AVX2
/// or AVX-512 batches, and the widths people use), so that the loops over the lanes below unroll;
/// as a plain number otherwise. The same operations in the same order either way: a lane's bits
/// do not depend on it.
template <class F> decltype(auto) with_lanes(std::size_t w, F&& f) {
    if (w == 8) return f(std::integral_constant<std::size_t, 8>{});
    if (w == 4) return f(std::integral_constant<std::size_t, 4>{});
    return f(w);
}
} // namespace detail

/// The Taylor method on a lane system (lanes.hpp): all lanes expanded together, one order and one
/// step for all of them, the smallest of the lanes' Jorba–Zou steps.
template <class T, class S> class taylor_lane_stepper {
  public:
    /// The floating-point type of the run.
    using scalar = T;
    /// The system type S this stepper integrates.
    using system_type = S;
    /// The state vector of S.
    using vector = state_vector<T, S>;
    /// What attempt() returns.
    using outcome = step_outcome<T>;

    static constexpr int order = 20; ///< nominal, as taylor_stepper's
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

    /// Storage for n state components (all lanes), with the options of m.
    taylor_lane_stepper(const taylor<T>& m, std::size_t n)
        : m_method(m), m_size(n), m_y1(vector::Zero(static_cast<Eigen::Index>(n))), m_f0(m_y1),
          m_comp(m_y1), m_comp_start(m_y1) {
        m_max_order = m.max_order();
        m_order_abs = m.order_of(false), m_order_rel = m.order_of(true);
        m_rule_abs = step_rule(m_order_abs), m_rule_rel = step_rule(m_order_rel);
    }

    /// Begins a run at (t0, y0): evaluates f(t0, y0); false when it is not finite.
    bool start(const S& sys, T t0, const vector& y0, step_stats& stats) {
        m_w = sys.lanes();
        m_n = sys.components();
        m_c.assign(m_size * static_cast<std::size_t>(m_max_order + 1), T(0));
        m_norm0.assign(m_w, T(0));
        m_inv_s.assign(m_w, T(1));
        m_relative.assign(m_w, 0);
        m_acc.assign(m_w, T(0));
        m_continued.assign(m_w, 0);
        m_weight = vector::Ones(static_cast<Eigen::Index>(m_size));
        m_weighted = m_method.layout.groups.size() == m_n;
        if (m_weighted) weighted_rules();
        expand(sys, t0, y0, stats);
        for (std::size_t i = 0; i < m_n; ++i)
            for (std::size_t l = 0; l < m_w; ++l)
                m_f0[static_cast<Eigen::Index>(i * m_w + l)] = at(i, 1)[l];
        return m_f0.allFinite();
    }
    /// f(t0, y0), after start() (for the initial step selection).
    const vector& f_start() const { return m_f0; }

    /// The smallest of the live lanes' steps from (t, y) (+inf when every series ends or no lane
    /// is live); expands the lanes there.
    T choose_step(const S& sys, T t, const vector& y, step_stats& stats) {
        if (!m_expanded) expand(sys, t, y, stats);
        const int p = m_p;
        const T inf = std::numeric_limits<T>::infinity();
        norms(p - 1, m_np1);
        norms(p, m_np);
        // ln is increasing, so the largest of the lanes' ln(||y^[k]|| / s) / k is ln of the
        // largest quotient over k: at most two logarithms a step, not two a lane, with the same
        // bits while every quotient is a normal number (step_rule takes another way otherwise).
        const step_rule rule = p == m_rule_rel.p   ? m_rule_rel
                               : p == m_rule_abs.p ? m_rule_abs
                                                   : step_rule(p); // no live lane
        T q1 = T(0), q = T(0);
        bool normal = true, live = false;
        for (std::size_t l = 0; l < m_w; ++l) {
            if (!sys.is_live(l)) continue;
            if (!(m_np1[l] == m_np1[l]) || !(m_np[l] == m_np[l]))
                return std::numeric_limits<T>::quiet_NaN();
            const T a = m_np1[l] * m_inv_s[l], b = m_np[l] * m_inv_s[l];
            normal = normal && std::isnormal(a) && std::isnormal(b);
            q1 = std::max(q1, a), q = std::max(q, b);
            live = true;
        }
        if (!live) return inf;
        T m = -inf;
        if (normal) {
            m = rule.max_ln_ratio(q1, q);
        } else {
            for (std::size_t l = 0; l < m_w; ++l)
                if (sys.is_live(l))
                    m = std::max(m, rule.ln_inverse_radius(m_np1[l], m_np[l],
                                                           m_relative[l] ? m_norm0[l] : T(1),
                                                           m_inv_s[l]));
        }
        if (m == -inf) return inf;
        return m_per_unit ? rule.step_per_unit(m, m_ln_span) : rule.step(m);
    }

    /// Each lane's y + sum_{k>=1} y^[k] h^k with Kahan's compensation carried from step to step,
    /// as taylor_stepper::attempt (a lane that did not continue from its last end, or is not live,
    /// starts it anew): one lane's run is its scalar run bit for bit.
    outcome attempt(const S& sys, T t, const vector& y, T h, step_stats& stats, bool) {
        if (!m_expanded) expand(sys, t, y, stats);
        m_h = h;
        for (std::size_t l = 0; l < m_w; ++l)
            m_continued[l] = m_stepped && sys.is_live(l) && continues(y, l);
        detail::with_lanes(m_w, [&](auto w) {
            T* r = m_acc.data();
            for (std::size_t i = 0; i < m_n; ++i) {
                tail(i, h, r, w);
                T* y1 = &m_y1[static_cast<Eigen::Index>(i * w)];
                T* comp = &m_comp[static_cast<Eigen::Index>(i * w)];
                T* start = &m_comp_start[static_cast<Eigen::Index>(i * w)];
                const T* y0 = &y[static_cast<Eigen::Index>(i * w)];
                for (std::size_t l = 0; l < w; ++l) {
                    start[l] = m_continued[l] ? comp[l] : T(0);
                    const T increment = h * r[l] - start[l];
                    y1[l] = y0[l] + increment;
                    comp[l] = (y1[l] - y0[l]) - increment;
                }
            }
        });
        m_stepped = true;
        return {m_y1.allFinite() ? status::ok : status::non_finite, T(0)};
    }

    /// The next step expands anew; the coefficients stay for dense(). Always true.
    bool accept(const S&, step_stats&, bool) {
        m_expanded = false;
        return true;
    }

    /// The state at t + h of the last attempt().
    const vector& y_new() const { return m_y1; }

    /// The interpolant of the last accepted step at θ = (t − t_n)/h in [0, 1], into out.
    void dense(T theta, vector& out) const {
        const T th = theta * m_h;
        detail::with_lanes(m_w, [&](auto w) {
            T* r = m_acc.data();
            for (std::size_t i = 0; i < m_n; ++i) {
                tail(i, th, r, w);
                const T* y0 = at(i, 0);
                const T* start = &m_comp_start[static_cast<Eigen::Index>(i * w)];
                T* o = &out[static_cast<Eigen::Index>(i * w)];
                for (std::size_t l = 0; l < w; ++l)
                    o[l] = y0[l] + (th * r[l] - start[l]);
            }
        });
    }

    /// The order of the last expansion.
    int last_order() const { return m_p; }

  private:
    /// Coefficient k of component i, all lanes.
    const T* at(std::size_t i, int k) const {
        return m_c.data() +
               (i * static_cast<std::size_t>(m_p + 1) + static_cast<std::size_t>(k)) * m_w;
    }
    T* at(std::size_t i, int k) { return const_cast<T*>(std::as_const(*this).at(i, k)); }

    /// Every lane's max_i |y_i^[k]| (NaN when one is not a number), into r.
    void norms(int k, std::vector<T>& r) const {
        using std::abs;
        r.assign(m_w, T(0));
        detail::with_lanes(m_w, [&](auto w) {
            T* m = r.data();
            for (std::size_t i = 0; i < m_n; ++i) {
                const T* c = at(i, k);
                for (std::size_t l = 0; l < w; ++l) {
                    const T v = abs(c[l]) * m_weight[static_cast<Eigen::Index>(i * m_w + l)];
                    m[l] = v == v ? std::max(m[l], v) : v; // NaN stays: max(NaN, v) is NaN
                }
            }
        });
    }

    /// Every lane's sum_{k>=1} y_i^[k] h^(k-1) (detail::series_sum, as taylor_stepper's), into
    /// r: a block of lanes at a time, its sums held in registers across the orders.
    /// w: the lane count, as with_lanes gives it (series_sums keeps a constant one's sums in
    /// registers).
    template <class W> void tail(std::size_t i, T h, T* r, W w) const {
        constexpr int lanes = std::is_integral_v<W> ? -1 : static_cast<int>(W{});
        const T* c = at(i, 1); // coefficient m + 1 of the lanes at c[m w + l]
        detail::series_sums<lanes>(m_p, h, w, {c, w, 1}, r);
    }

    /// Whether lane l of y is the last step's end.
    bool continues(const vector& y, std::size_t l) const {
        for (std::size_t i = 0; i < m_n; ++i) {
            const auto e = static_cast<Eigen::Index>(i * m_w + l);
            if (!(y[e] == m_y1[e])) return false;
        }
        return true;
    }

    /// Each lane's control, the shared order, then the coefficients of every lane.
    void expand(const S& sys, T t, const vector& y, step_stats& stats) {
        using std::abs;
        const taylor<T>& m = m_method;
        std::fill(m_norm0.begin(), m_norm0.end(), T(0));
        for (std::size_t i = 0; i < m_n; ++i)
            for (std::size_t l = 0; l < m_w; ++l)
                m_norm0[l] = std::max(m_norm0[l], abs(y[static_cast<Eigen::Index>(i * m_w + l)]));
        int p = m.order > 0 ? m.order : 2;
        for (std::size_t l = 0; l < m_w; ++l) {
            m_relative[l] = m.rtol > T(0) && m.rtol * m_norm0[l] > m.atol;
            m_inv_s[l] = m_relative[l] ? T(1) / m_norm0[l] : T(1); // see taylor<T>::step_rule
            if (m.order == 0 && sys.is_live(l))
                p = std::max(p, m_relative[l] ? m_order_rel : m_order_abs);
        }
        if (m_weighted) {
            weigh(y);
            if (m.order == 0) p = m.rtol > T(0) ? m_order_rel : m_order_abs;
        }
        m_p = p;
        for (std::size_t i = 0; i < m_n; ++i)
            for (std::size_t l = 0; l < m_w; ++l)
                at(i, 0)[l] = y[static_cast<Eigen::Index>(i * m_w + l)];
        sys.taylor(t, m_c.data(), m_p);
        ++stats.rhs_evals;
        m_expanded = true;
    }

    /// The weighted control under a layout, as taylor_stepper's (each lane's scales its own).
    void weighted_rules() {
        using std::log;
        const taylor<T>& m = m_method;
        const T f = calibration_factor(m.calibration_scale, m.calibration_power, m.rtol, m.atol);
        if (m.rtol > T(0)) m_rule_rel = step_rule(m_order_rel, log(f * m.rtol));
        if (m.atol > T(0)) m_rule_abs = step_rule(m_order_abs, log(f * m.atol));
        m_per_unit = m.layout.span > 0;
        if (m_per_unit) m_ln_span = log(T(m.layout.span));
    }
    void weigh(const vector& y) {
        const taylor<T>& m = m_method;
        detail::inverse_scales(m.layout, y, y, m.atol, m.rtol, m_w, m_weight);
        m_weight *= m.rtol > T(0) ? m.rtol : m.atol;
        for (std::size_t l = 0; l < m_w; ++l)
            m_relative[l] = m.rtol > T(0), m_norm0[l] = T(1), m_inv_s[l] = T(1);
    }

    taylor<T> m_method;
    std::size_t m_size, m_n = 0, m_w = 1;
    int m_max_order = 2, m_p = 2;
    int m_order_abs = 2, m_order_rel = 2; ///< the order of each control (taylor<T>::order_of)
    using step_rule = typename taylor<T>::step_rule;
    step_rule m_rule_abs, m_rule_rel; ///< the step rule of each control's order
    bool m_per_unit = false;          ///< the weighted control per unit step (error_layout::span)
    T m_ln_span = T(0);               ///< ln of error_layout::span when m_per_unit
    bool m_expanded = false;
    std::vector<T> m_c, m_norm0, m_inv_s;
    std::vector<T> m_np1, m_np; ///< each lane's norm of y^[p-1] and y^[p] (choose_step)
    std::vector<char> m_relative;
    mutable std::vector<T> m_acc; ///< Horner's running values, one per lane
    T m_h = T(0);
    vector m_y1, m_f0;
    vector m_comp, m_comp_start;   ///< Kahan's compensation of m_y1, and of the step's start
    std::vector<char> m_continued; ///< per lane: this step continues from the last step's end
    bool m_stepped = false;
    vector m_weight;         ///< w of norms(): 1, or eps / sk under a layout (weigh())
    bool m_weighted = false; ///< the layout has groups: the weighted control
};

} // namespace rotgen
