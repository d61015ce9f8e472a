/// \file
/// rotgen runtime — the free rigid body's angular momentum in body axes, m(t), in Jacobi elliptic
/// functions, and the precession angle ψ(t) of the attitude formula (flow.hpp), for three distinct
/// principal moments. The sphere, the symmetric top and a spin about a principal axis are handled
/// apart in flow.hpp (the formulas here divide by moment differences and by the transverse
/// momentum).
///
/// Frames: the body axes are first relabelled so that the moments increase, by a proper signed
/// permutation (an odd permutation also flips the middle axis, so that Euler's equations ṁ = m × ω
/// keep their form); then, when G² > 2T I2 (the polhode circles the axis of the largest moment), by
/// (I1, I2, I3) → (I3, I2, I1), (ω1, ω2, ω3) → (ω3, −ω2, ω1) (exact_free_top.hpp). In that frame j:
///   ω1 = s1 A1 dn(u),  ω2 = σ A2 sn(u),  ω3 = A3 cn(u),  u = λ t + u0,
///   A1² = h/(j1 (j3 − j1)),  A2² = l/(j2 (j2 − j1)),  A3² = l/(j3 (j3 − j1)),
///   λ² = (j2 − j1) h/(j1 j2 j3),  m = k² = (j3 − j2) l/((j2 − j1) h),
///   mc = 1 − k² = (j3 − j1) g/((j2 − j1) h),                       (Leroy; see flow.hpp)
///   h = 2T j3 − G² = Σ j_i (j3 − j_i) ω_i²,  l = G² − 2T j1 = Σ j_i (j_i − j1) ω_i²,
///   g = 2T j2 − G² = Σ j_i (j2 − j_i) ω_i²     (sums of terms of one sign: no cancellation),
///   s1 = sgn ω1(0), σ = s1 sgn(j3 − j1), and u0 = F(φ0 | m) with φ0 = atan2(ω2/(σ A2), ω3/A3).
/// F is continued over half periods by F(jπ + r) = 2jK + F(r) (A&S 17.4.3).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <utility>

#include "amplitude.hpp"
#include "small_parameter.hpp"

namespace rotgen::detail {

/// The index of the moment that differs from the other two (0 for a sphere), −1 if all differ.
template <class T> int distinct_axis(const std::array<T, 3>& in) {
    if (in[0] == in[1]) return in[1] == in[2] ? 0 : 2;
    if (in[1] == in[2]) return 0;
    if (in[0] == in[2]) return 1;
    return -1;
}

template <class T> bool all_equal(const std::array<T, 3>& in) {
    return in[0] == in[1] && in[1] == in[2];
}

/// Two components exactly zero: m lies on a principal axis and stays there.
template <class V> bool on_principal_axis(const V& m) {
    using S = std::decay_t<decltype(m[0])>;
    return (m[0] == S(0)) + (m[1] == S(0)) + (m[2] == S(0)) >= 2;
}

template <class T> struct momentum_at {
    std::array<T, 3> m;  ///< body angular momentum, original body axes
    jacobi_values<T> jv; ///< at u = λ t + u0
};

template <class T> class free_body_momentum {
  public:
    free_body_momentum(const std::array<T, 3>& in, const std::array<T, 3>& m0) : m_in(in) {
        sort_axes();
        std::array<T, 3> v{};
        for (int i = 0; i < 3; ++i)
            v[i] = signed_component(m0, i) / m_in[m_perm[i]];
        m_j = {m_in[m_perm[0]], m_in[m_perm[1]], m_in[m_perm[2]]};
        T g_mid = 0, twice_t = 0;
        for (int i = 0; i < 3; ++i) {
            g_mid += m_j[i] * (m_j[1] - m_j[i]) * v[i] * v[i];
            twice_t += m_j[i] * v[i] * v[i];
            m_g2 += m_j[i] * m_j[i] * v[i] * v[i];
        }
        m_flip = g_mid < T(0);
        if (m_flip) {
            std::swap(m_j[0], m_j[2]);
            v = {v[2], -v[1], v[0]}; // g_mid = 2T j2 − G² is the same in both frames
        }
        m_twice_t = twice_t;
        amplitudes(v, g_mid);
    }

    T g() const {
        using std::sqrt;
        return sqrt(m_g2);
    }
    int axis() const { return m_perm[m_flip ? 2 : 0]; } // the dn axis, original index
    int axis_sign() const { return m_s1 > T(0) ? 1 : -1; }

    momentum_at<T> at(T t) const {
        momentum_at<T> r;
        r.jv = m_amp(m_lambda * t + m_u0);
        std::array<T, 3> w = {m_s1 * m_a1 * r.jv.dn, m_sigma * m_a2 * r.jv.sn, m_a3 * r.jv.cn};
        if (m_flip) w = {w[2], -w[1], w[0]};
        const std::array<T, 3> js = {m_in[m_perm[0]], m_in[m_perm[1]], m_in[m_perm[2]]};
        for (int i = 0; i < 3; ++i)
            r.m[m_perm[i]] = (i == 1 && m_odd ? -T(1) : T(1)) * js[i] * w[i];
        return r;
    }

    /// ψ(t) of flow.hpp, given the state at t from at(t).
    T precession(T t, const momentum_at<T>& end) const {
        // Δ_e = G² − 2T I_e = Σ_i m_i² (I_i − I_e)/I_i = l, the invariant of the file comment
        const T g = this->g();
        const T w1 = m_use_series ? m_series.at(end.jv.half_periods, end.jv.reduced_am).w
                                  : w_of(end.jv.half_periods, end.jv.reduced_am, end.jv.reduced_u);
        return m_twice_t * t / g + m_l / (m_j[0] * g) * (t - (w1 - m_w0) / m_lambda);
    }

  private:
    void sort_axes() {
        m_perm = {0, 1, 2};
        std::sort(m_perm.begin(), m_perm.end(), [&](int a, int b) { return m_in[a] < m_in[b]; });
        // parity of the permutation: even permutations of (0 1 2) are its rotations
        m_odd = !((m_perm[1] == (m_perm[0] + 1) % 3) && (m_perm[2] == (m_perm[1] + 1) % 3));
    }
    T signed_component(const std::array<T, 3>& m, int i) const {
        return (i == 1 && m_odd ? -T(1) : T(1)) * m[m_perm[i]];
    }

    void amplitudes(const std::array<T, 3>& v, T g_mid) {
        using std::atan2;
        using std::sqrt;
        T h = 0, l = 0;
        for (int i = 0; i < 3; ++i) {
            h += m_j[i] * (m_j[2] - m_j[i]) * v[i] * v[i];
            l += m_j[i] * (m_j[i] - m_j[0]) * v[i] * v[i];
        }
        const std::array<T, 3>& j = m_j;
        m_l = l;
        m_a1 = sqrt(h / (j[0] * (j[2] - j[0])));
        m_a2 = sqrt(l / (j[1] * (j[1] - j[0])));
        m_a3 = sqrt(l / (j[2] * (j[2] - j[0])));
        m_lambda = sqrt((j[1] - j[0]) * h / (j[0] * j[1] * j[2]));
        const T k2 = std::min(T(1), (j[2] - j[1]) * l / ((j[1] - j[0]) * h));
        const T mc = std::max(T(0), (j[2] - j[0]) * g_mid / ((j[1] - j[0]) * h));
        m_amp = jacobi_amplitude<T>(k2, mc);
        m_s1 = v[0] >= T(0) ? T(1) : T(-1);
        m_sigma = m_s1 * (j[2] > j[0] ? T(1) : T(-1));
        const T big_a = j[0] * m_a1; // A
        m_use_series = k2 <= small_parameter_limit<T>;
        if (m_use_series)
            m_series = phase_series<T>(k2, sqrt(m_g2), big_a);
        else
            carlson_constants(big_a, k2);
        start_phase(atan2(v[1] / (m_sigma * m_a2), v[2] / m_a3));
    }

    /// W's constants: A = j1 A1, c = (j3 A3)², c + d = (j2 A2)², n = −d/c, d = A² k².
    void carlson_constants(T big_a, T k2) {
        using std::sqrt;
        const std::array<T, 3>& j = m_j;
        m_c = j[2] * m_a3 * j[2] * m_a3;
        m_cd = j[1] * m_a2 * j[1] * m_a2;
        m_n = -(big_a * big_a * k2) / m_c;
        m_coef_pi = m_g2 / m_c;
        m_coef_atan = sqrt(m_g2) * big_a / sqrt(m_c * m_cd);
    }

    /// u0 = F(φ0) and W(u0) from the amplitude φ0 ∈ (−π, π] (one R_F serves both).
    void start_phase(T phi0) {
        using std::cos;
        using std::sin;
        const T pi = boost::math::constants::pi<T>();
        long long j = 0;
        if (phi0 > pi / T(2)) j = 1;
        if (phi0 < -pi / T(2)) j = -1;
        const T r = phi0 - T(j) * pi;
        if (m_use_series) {                    // small m: the series of small_parameter.hpp
            const auto ps = m_series.at(j, r); // F(jπ + r) = 2jK + F(r)
            m_u0 = ps.f;
            m_w0 = ps.w;
            return;
        }
        const T s = sin(r), c = cos(r);
        const auto fp = incomplete_integrals(m_n, s, c, delta2(c));
        m_u0 = T(2) * T(j) * m_amp.complete_k() + fp.f;
        m_w0 = w_of(j, s, c, fp.pi);
    }

    T delta2(T c) const { return m_amp.complement() + m_amp.parameter() * c * c; }

    /// W(2K j + r) = j W(2K) + W(r), from s = sin am r, c = cos am r and Π(am r; n | m).
    T w_of(long long j, T s, T c, T pi_incomplete) const {
        using std::atan2;
        using std::sqrt;
        T w = m_coef_pi * pi_incomplete - m_coef_atan * atan2(sqrt(m_cd) * s, sqrt(m_c) * c);
        if (j != 0) {
            if (!m_w_period_known) { // W(2K), once per flow (mc > 0 here: K is finite)
                const T pi_c = complete_pi(m_n, m_amp.complement(), m_amp.complete_k());
                m_w_period =
                    T(2) * (m_coef_pi * pi_c - m_coef_atan * boost::math::constants::half_pi<T>());
                m_w_period_known = true;
            }
            w += T(j) * m_w_period;
        }
        return w;
    }
    /// The same from am(r) and r = F(am r) (jacobi_values): no R_F.
    T w_of(long long j, T reduced_am, T reduced_u) const {
        using std::cos;
        using std::sin;
        const T s = sin(reduced_am), c = cos(reduced_am);
        return w_of(j, s, c, incomplete_pi(m_n, reduced_u, s, c, delta2(c)));
    }

    std::array<T, 3> m_in;
    std::array<int, 3> m_perm{};
    bool m_odd = false, m_flip = false;
    std::array<T, 3> m_j{};
    T m_g2 = 0, m_twice_t = 0, m_l = 0;
    T m_a1 = 0, m_a2 = 0, m_a3 = 0, m_lambda = 0, m_s1 = 1, m_sigma = 1, m_u0 = 0;
    jacobi_amplitude<T> m_amp{T(0), T(1)};
    T m_c = 0, m_cd = 0, m_n = 0, m_coef_pi = 0, m_coef_atan = 0, m_w0 = 0;
    bool m_use_series = false; ///< m <= small_parameter_limit: W and F by phase_series
    phase_series<T> m_series{T(0), T(1), T(1)};
    mutable T m_w_period = 0;
    mutable bool m_w_period_known = false;
};

} // namespace rotgen::detail
