// rotgen bench — the exact motion of a force-free rigid body in principal axes, for the
// work-precision reference: the body angular velocity omega(t) AND the attitude A(t).
//
// omega(t):
//   asymmetric top (three different moments, any order): rotgen::free_top_exact
//     (runtime/exact_free_top.hpp, Jacobi elliptic functions) in a relabelled frame where
//     I1 < I2 < I3. Euler's equations I omega' = (I omega) x omega keep their form under any proper
//     rotation of the body axes, so the axes are permuted by a signed permutation of determinant +1
//     (an odd permutation flips the sign of one axis).
//   symmetric top (two equal moments, made axes 1 and 2): omega3 is constant and
//     omega1 + i omega2 = (omega1(0) + i omega2(0)) exp(i Omega t), Omega = (I3 - I1)/I1 omega3.
//   spherical top: omega is constant.
// A(t), passive, body <- space (5.25), from the conservation of the space angular momentum L:
//   in a space frame s' whose z axis is along L and a relabelled body frame b' (a cyclic, hence
//   proper, permutation Q of the body axes that makes the chart axis c the third one), the
//   z-x-z Euler angles of A' = Q A B^T are
//     cos(theta') = l'3 / |L|,   psi' = atan2(l'1, l'2)     (l' = Q I omega: A' e_z |L| = l')
//     phi'_dot = |L| (I'1 omega'1^2 + I'2 omega'2^2) / (l'1^2 + l'2^2)
//   (from (5.30): omega'1 sin(psi') + omega'2 cos(psi') = phi'_dot sin(theta')), and phi'(t) is
//   its integral from phi'(0) = 0 by Gauss-Kronrod quadrature (61 points, adaptive, on pieces of
//   1/16 of the period of omega). B = A'(0)^T Q A0 fixes the frame s' from the initial attitude,
//   and A(t) = Q^T A'(t) B. The chart axis c is one that L never reaches: the intermediate axis of
//   an asymmetric top (off the separatrix omega1 or omega3 never vanishes), the symmetry axis of
//   a symmetric top (theta' is constant) unless L lies along it, then a transverse axis.
// Exact up to the quadrature (~1e-18 relative in long double) and Boost's elliptic functions.
#pragma once

#include "exact_free_top.hpp" // rotgen::free_top_exact (runtime/)
#include "rotation.hpp"       // euler_matrix, mat3

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

namespace rotgen::bench {

template <class T> class free_body_exact {
  public:
    using vec3 = std::array<T, 3>;

    // I: principal moments (> 0); w0: body angular velocity at t = 0; a0: the attitude at t = 0.
    free_body_exact(vec3 I, vec3 w0, const mat3<T>& a0) : m_I(I), m_w0(w0), m_a0(a0) {
        using std::abs;
        using std::sqrt;
        for (T i : I)
            if (!(i > T(0))) throw std::invalid_argument("free_body_exact: moments must be > 0");
        const bool e01 = I[0] == I[1], e12 = I[1] == I[2], e02 = I[0] == I[2];
        if (e01 && e12) {
            m_kind = kind::spherical;
        } else if (e01 || e12 || e02) {
            m_kind = kind::symmetric;
            // the distinct axis becomes the third one, by a cyclic (proper) permutation
            const int distinct = e01 ? 2 : e12 ? 0 : 1;
            m_perm = {(distinct + 1) % 3, (distinct + 2) % 3, distinct};
            m_sign = {T(1), T(1), T(1)};
            const vec3 w = relabel(w0);
            m_omega_sym = (I[m_perm[2]] - I[m_perm[0]]) / I[m_perm[0]] * w[2];
        } else {
            m_kind = kind::asymmetric;
            // the signed permutation that sorts the moments, with determinant +1
            std::array<int, 3> p = {0, 1, 2};
            std::sort(p.begin(), p.end(), [&](int a, int b) { return I[a] < I[b]; });
            m_perm = p;
            const int inversions = (p[0] > p[1]) + (p[0] > p[2]) + (p[1] > p[2]);
            m_sign = {T(1), inversions % 2 ? T(-1) : T(1), T(1)};
            m_top =
                std::make_shared<free_top_exact<T>>(vec3{I[p[0]], I[p[1]], I[p[2]]}, relabel(w0));
        }
        // the attitude: the chart axis, |L|, and the fixed frame B
        const vec3 l = momentum(w0);
        m_L = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
        if (m_kind == kind::asymmetric) {
            m_chart = m_perm[1]; // the intermediate axis
        } else if (m_kind == kind::symmetric) {
            const int axis = m_perm[2];
            const T across = sqrt(l[m_perm[0]] * l[m_perm[0]] + l[m_perm[1]] * l[m_perm[1]]);
            m_chart = across > T(1e-8) * m_L ? axis : m_perm[0];
        } else {
            int c = 0;
            for (int i = 1; i < 3; ++i)
                if (abs(l[i]) < abs(l[c])) c = i;
            m_chart = c;
        }
        m_period = period();
        m_b = chart_matrix(T(0), w0).transpose() * q_matrix() * m_a0; // B = A'(0)^T Q A0
    }

    // omega(t) in body axes
    vec3 omega(T t) const {
        using std::cos;
        using std::sin;
        switch (m_kind) {
        case kind::spherical:
            return m_w0;
        case kind::symmetric: {
            const vec3 w = relabel(m_w0);
            const T c = cos(m_omega_sym * t), s = sin(m_omega_sym * t);
            return unlabel({w[0] * c - w[1] * s, w[0] * s + w[1] * c, w[2]});
        }
        case kind::asymmetric:
            return unlabel((*m_top)(t));
        }
        return m_w0;
    }

    // A(t), passive, body <- space (5.25)
    mat3<T> rotation(T t) const {
        return q_matrix().transpose() * chart_matrix(phi_chart(t), omega(t)) * m_b;
    }

    // Period of omega (infinite for a spherical top or a symmetric top spinning about its axis).
    T period() const {
        using std::abs;
        switch (m_kind) {
        case kind::asymmetric:
            return m_top->period();
        case kind::symmetric:
            return m_omega_sym != T(0) ? T(2) * T(EIGEN_PI) / abs(m_omega_sym)
                                       : std::numeric_limits<T>::infinity();
        case kind::spherical:
            break;
        }
        return std::numeric_limits<T>::infinity();
    }

    const char* kind_name() const {
        return m_kind == kind::asymmetric  ? "asymmetric"
               : m_kind == kind::symmetric ? "symmetric"
                                           : "spherical";
    }

  private:
    enum class kind { asymmetric, symmetric, spherical };

    vec3 momentum(const vec3& w) const { return {m_I[0] * w[0], m_I[1] * w[1], m_I[2] * w[2]}; }
    // body -> relabelled frame of the omega solution: w'_k = sign_k w_{perm_k}
    vec3 relabel(const vec3& w) const {
        return {m_sign[0] * w[m_perm[0]], m_sign[1] * w[m_perm[1]], m_sign[2] * w[m_perm[2]]};
    }
    vec3 unlabel(const vec3& v) const {
        vec3 w{};
        for (int k = 0; k < 3; ++k)
            w[m_perm[k]] = m_sign[k] * v[k];
        return w;
    }
    // Q: b' = Q b, b'_k = b_{(c + 1 + k) mod 3}
    mat3<T> q_matrix() const {
        mat3<T> q = mat3<T>::Zero();
        for (int k = 0; k < 3; ++k)
            q(k, (m_chart + 1 + k) % 3) = T(1);
        return q;
    }
    // A'(phi', theta'(w), psi'(w))
    mat3<T> chart_matrix(T phi, const vec3& w) const {
        using std::atan2;
        using std::sqrt;
        const vec3 l = momentum(w);
        const int i1 = (m_chart + 1) % 3, i2 = (m_chart + 2) % 3;
        const T theta = atan2(sqrt(l[i1] * l[i1] + l[i2] * l[i2]), l[m_chart]);
        const T psi = atan2(l[i1], l[i2]);
        return euler_matrix(phi, theta, psi);
    }
    T phi_rate(T t) const {
        const vec3 w = omega(t);
        const int i1 = (m_chart + 1) % 3, i2 = (m_chart + 2) % 3;
        const T l1 = m_I[i1] * w[i1], l2 = m_I[i2] * w[i2];
        return m_L * (l1 * w[i1] + l2 * w[i2]) / (l1 * l1 + l2 * l2);
    }
    T phi_chart(T t) const {
        using std::ceil;
        using std::isfinite;
        using std::max;
        if (t == T(0)) return T(0);
        const T piece = isfinite(m_period) ? m_period / T(16) : t;
        const long n = std::max(1L, static_cast<long>(ceil(t / piece)));
        T sum = T(0);
        const auto f = [this](T s) { return phi_rate(s); };
        for (long i = 0; i < n; ++i) {
            const T a = t * T(i) / T(n), b = t * T(i + 1) / T(n);
            T err = T(0);
            sum += boost::math::quadrature::gauss_kronrod<T, 61>::integrate(
                f, a, b, 3, T(64) * std::numeric_limits<T>::epsilon(), &err);
        }
        return sum;
    }

    vec3 m_I, m_w0;
    mat3<T> m_a0, m_b;
    kind m_kind = kind::asymmetric;
    std::array<int, 3> m_perm{{0, 1, 2}};
    vec3 m_sign{{T(1), T(1), T(1)}};
    T m_omega_sym = T(0), m_L = T(0), m_period = T(0);
    int m_chart = 2;
    std::shared_ptr<free_top_exact<T>> m_top;
};

} // namespace rotgen::bench
