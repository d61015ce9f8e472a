/// \file
/// rotgen runtime — where an event function may change sign on one step, proven or excluded
/// (events.hpp's search; the approach of Chebfun's root finder, Battles & Trefethen, SIAM J. Sci.
/// Comput. 25 (2004) 1743–1770, with the exclusion by a bound on the second derivative).
///
/// g(theta), theta in [0, 1], is the event function on the step's interpolant. A piece [a, b] of
/// the step is fitted by the Chebyshev interpolant p of degree n = 8 on the points of the second
/// kind
///   theta_j = a + (b − a) (1 − cos(pi j / n)) / 2,  j = 0..n   (both ends among them),
///   p(x) = sum_k c_k T_k(x),  x = 2 (theta − a) / (b − a) − 1.
/// The fit's error eps is the sum of its last three coefficients, or rounding (1e-13 of g's size
/// on the whole step) if that is larger; the fit counts as resolved when eps is below 1e-6 of g's
/// size on the piece, or at rounding. An unresolved piece is halved (its middle point is a node
/// already: 7 new values of g per half). On a resolved piece p's sign changes
/// are isolated by bisection in x, each part [u, v] (values pu, pv) ending as
///   excluded  pu, pv of one sign and min(|pu|, |pv|) > M2 (v − u)² / 8 + eps, M2 = sum |c_k|
///             k²(k² − 1)/3 >= max |p''| (|T_k''| <= T_k''(1)): p is above its chord minus
///             M2 (v − u)² / 8, so g has no zero in [u, v];
///   monotone  |p'((u + v)/2)| > M2 (v − u) / 2: p' keeps its sign, so p has one zero in [u, v]
///   when
///             pu and pv differ in sign and none otherwise;
/// or undecided after 12 halvings: the piece is then halved and fitted again, down to `min_width`,
/// and what stays undecided is reported as an interval where a pair of zeros may hide (a zero where
/// g only touches 0 ends so).
/// The result is a list of points (theta, p) whose consecutive sign changes are the zeros of g, and
/// the undecided intervals.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace rotgen::detail {

template <class T> class event_roots {
  public:
    static constexpr int n = 8;

    struct point {
        T theta, value;
    };
    struct interval {
        T from, to;
    };

    /// theta of node j of the piece [a, b]
    static T node(T a, T b, int j) { return a + (b - a) * cosines()[j]; }

    /// Searches [0, 1] given g at the nodes of the whole step (`f`, n + 1 values), g(theta) for
    /// other points, the narrowest piece to fit and the most pieces to fit.
    template <class G>
    void run(const std::array<T, n + 1>& f, const G& g, T min_width, std::size_t max_pieces) {
        m_points.assign(1, {T(0), f[0]});
        m_undecided.clear();
        m_pieces = 0;
        m_max_pieces = max_pieces;
        m_min_width = min_width;
        m_curvature = T(0);
        m_floor = T(0);
        for (const T v : f)
            m_floor = std::max(m_floor, T(1e-13) * std::abs(v));
        piece(T(0), T(1), f, g);
    }

    const std::vector<point>& points() const { return m_points; }
    const std::vector<interval>& undecided() const { return m_undecided; }
    std::size_t pieces() const { return m_pieces; }
    /// max |g''| on the step as the fits bound it (per theta²)
    T curvature() const { return m_curvature; }

  private:
    using coefficients = std::array<T, n + 1>;
    struct part { // [u, v] in x with p there, after `depth` halvings
        T u, pu, v, pv;
        int depth;
    };

    /// (1 − cos(pi j / n)) / 2
    static const std::array<T, n + 1>& cosines() {
        static const std::array<T, n + 1> c = [] {
            std::array<T, n + 1> v{};
            const T pi = T(3.141592653589793238462643383279502884L);
            for (int j = 0; j <= n; ++j)
                v[static_cast<std::size_t>(j)] = (T(1) - std::cos(pi * T(j) / T(n))) / T(2);
            v[n / 2] = T(0.5);
            return v;
        }();
        return c;
    }

    /// T_k(x_j) = cos(pi k (n − j) / n), weighted by 1/2 at j = 0, n and by (2/n), halved again
    /// for k = 0, n: c = W f
    static const std::array<std::array<T, n + 1>, n + 1>& weights() {
        static const auto w = [] {
            std::array<std::array<T, n + 1>, n + 1> m{};
            const T pi = T(3.141592653589793238462643383279502884L);
            for (int k = 0; k <= n; ++k)
                for (int j = 0; j <= n; ++j)
                    m[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)] =
                        std::cos(pi * T(k * (n - j)) / T(n)) * T(2) / T(n) *
                        ((j == 0 || j == n) ? T(0.5) : T(1)) * ((k == 0 || k == n) ? T(0.5) : T(1));
            return m;
        }();
        return w;
    }

    /// c_k = (2/n) sum_j'' f_j T_k(x_j), halved for k = 0 and n (x_j = −cos(pi j / n) ascending)
    static coefficients fit(const std::array<T, n + 1>& f) {
        const auto& w = weights();
        coefficients c{};
        for (std::size_t k = 0; k <= n; ++k) {
            T s = T(0);
            for (std::size_t j = 0; j <= n; ++j)
                s += w[k][j] * f[j];
            c[k] = s;
        }
        return c;
    }

    /// Clenshaw: sum_k c_k T_k(x)
    template <std::size_t N> static T clenshaw(const std::array<T, N>& c, T x) {
        T b1 = T(0), b2 = T(0);
        for (std::size_t k = N - 1; k >= 1; --k) {
            const T b0 = T(2) * x * b1 - b2 + c[k];
            b2 = b1, b1 = b0;
        }
        return x * b1 - b2 + c[0];
    }

    /// p' = sum_k d_k T_k: d_{k−1} = d_{k+1} + 2 k c_k, d_0 halved
    static coefficients derivative(const coefficients& c) {
        coefficients d{};
        for (int k = n; k >= 1; --k) {
            const auto ku = static_cast<std::size_t>(k);
            d[ku - 1] = (ku + 1 <= n ? d[ku + 1] : T(0)) + T(2 * k) * c[ku];
        }
        d[0] /= T(2);
        return d;
    }

    template <class G> void piece(T a, T b, const std::array<T, n + 1>& f, const G& g) {
        using std::abs;
        ++m_pieces;
        const coefficients c = fit(f);
        T scale = T(0), m2 = T(0);
        for (int j = 0; j <= n; ++j) {
            scale = std::max(scale, abs(f[static_cast<std::size_t>(j)]));
            const T k2 = T(j * j);
            m2 += abs(c[static_cast<std::size_t>(j)]) * k2 * (k2 - T(1)) / T(3);
        }
        const T eps =
            std::max(abs(c[n - 2]) + abs(c[n - 1]) + abs(c[n]) + T(1e-14) * scale, m_floor);
        const bool can_split = b - a > m_min_width && m_pieces + 2 <= m_max_pieces;
        const bool resolved = eps <= std::max(T(1e-6) * scale, m_floor);
        if (!resolved && can_split) return split(a, b, f, g);
        const std::size_t mark = m_points.size(), undecided = m_undecided.size();
        if (scale == T(0)) { // g = 0 on the piece: no sign change
            m_points.push_back({b, f[n]});
            return;
        }
        const bool decided = resolved && isolate(a, b, c, m2, eps);
        if (!decided && can_split) {
            m_points.resize(mark);
            m_undecided.resize(undecided);
            return split(a, b, f, g);
        }
        m_curvature = std::max(m_curvature, m2 * T(4) / ((b - a) * (b - a)));
        if (!resolved) { // and no more splitting: its nodes, and a warning
            for (int j = 1; j <= n; ++j)
                m_points.push_back({node(a, b, j), f[static_cast<std::size_t>(j)]});
            m_undecided.push_back({a, b});
        }
    }

    template <class G> void split(T a, T b, const std::array<T, n + 1>& f, const G& g) {
        const T m = node(a, b, n / 2);
        std::array<T, n + 1> left{}, right{};
        left[0] = f[0], left[n] = f[n / 2];
        right[0] = f[n / 2], right[n] = f[n];
        for (int j = 1; j < n; ++j) {
            left[static_cast<std::size_t>(j)] = g(node(a, m, j));
            right[static_cast<std::size_t>(j)] = g(node(m, b, j));
        }
        piece(a, m, left, g);
        piece(m, b, right, g);
    }

    /// Bisection of the resolved piece [a, b] into excluded and monotone parts; pushes the parts'
    /// right ends (theta, p). False when a part stays undecided (then recorded in m_undecided).
    bool isolate(T a, T b, const coefficients& c, T m2, T eps) {
        const coefficients d = derivative(c);
        bool decided = true;
        std::vector<part>& stack = m_stack;
        stack.assign(1, {T(-1), clenshaw(c, T(-1)), T(1), clenshaw(c, T(1)), 0});
        const auto theta = [&](T x) { return a + (b - a) * (x + T(1)) / T(2); };
        while (!stack.empty()) {
            const part q = stack.back();
            stack.pop_back();
            using std::abs;
            const T w = q.v - q.u;
            const bool same = (q.pu > T(0)) == (q.pv > T(0)) && q.pu != T(0) && q.pv != T(0);
            const bool excluded = same && std::min(abs(q.pu), abs(q.pv)) > m2 * w * w / T(8) + eps;
            const bool monotone = abs(clenshaw(d, (q.u + q.v) / T(2))) > m2 * w / T(2);
            if (excluded || monotone || q.depth >= 12) {
                if (!excluded && !monotone) {
                    decided = false;
                    m_undecided.push_back({theta(q.u), theta(q.v)});
                }
                m_points.push_back({theta(q.v), q.pv});
                continue;
            }
            const T xm = (q.u + q.v) / T(2), pm = clenshaw(c, xm);
            stack.push_back({xm, pm, q.v, q.pv, q.depth + 1}); // the right half after the left
            stack.push_back({q.u, q.pu, xm, pm, q.depth + 1});
        }
        return decided;
    }

    std::vector<point> m_points;
    std::vector<interval> m_undecided;
    std::vector<part> m_stack;
    std::size_t m_pieces = 0, m_max_pieces = 0;
    T m_min_width = T(0), m_curvature = T(0);
    T m_floor = T(0); ///< rounding: 1e-13 of g's largest value at the step's nodes
};

} // namespace rotgen::detail
