/// \file
/// rotgen runtime — the twelve Euler-angle sequences, numerically.
///
/// A sequence a-b-c (axes 0 = x, 1 = y, 2 = z) names three angles (α, β, γ): α about the space
/// axis a, then β about the new axis b, then γ about the newest axis c. The matrix is PASSIVE,
/// body ← space, as (5.25) is for z-x-z:
///   A = A_c(γ) A_b(β) A_a(α),  A_n(x) the elementary passive rotation about axis n (5.8, 5.9):
///   A_n[u][u] = A_n[v][v] = cos x, A_n[u][v] = sin x, A_n[v][u] = −sin x, (n, u, v) cyclic.
/// z-x-z is (φ, θ, ψ) of the chapter. Proper Euler sequences (a = c: zxz zyz xyx xzx yxy yzy) have
/// β ∈ [0, π], α, γ ∈ [0, 2π), singular at β = 0, π (sin β = 0); Tait–Bryan sequences (a, b, c
/// all different: zyx zxy yxz yzx xyz xzy) have β ∈ [−π/2, π/2], α, γ ∈ (−π, π], singular at
/// β = ±π/2 (cos β = 0). At the singularity γ = 0 and the whole turn goes into α.
///
/// The body angular velocity is ω = J q̇ with the columns of J the rotation axes, each carried into
/// body axes by the rotations after it:  J = [A_c(γ) A_b(β) e_a | A_c(γ) e_b | e_c]  (5.30 for
/// z-x-z). The quaternion (scalar first, active, R(q) = Aᵀ, as rotation.hpp) is
///   q = q_a(α) ⊗ q_b(β) ⊗ q_c(γ),  q_n(x) = (cos x/2, e_n sin x/2).
#pragma once

#include "rotation.hpp"

#include <array>
#include <cmath>
#include <limits>

namespace rotgen {

/// An Euler-angle sequence a-b-c: the axes of the three elementary rotations (0 = x, 1 = y, 2 = z).
struct euler_sequence {
    std::array<int, 3> axes{2, 0, 2}; ///< z-x-z

    /// True for a proper Euler sequence (first axis = last axis, e.g. z-x-z); false for Tait–Bryan.
    bool proper() const { return axes[0] == axes[2]; }
    /// The axis that is neither the first nor the second.
    int other() const { return 3 - axes[0] - axes[1]; }
    /// +1 when (a, b, other) is a cyclic permutation of (x, y, z), else −1.
    int parity() const { return (axes[1] - axes[0] + 3) % 3 == 1 ? 1 : -1; }
    /// True for the chapter's z-x-z (φ, θ, ψ).
    bool is_zxz() const { return axes[0] == 2 && axes[1] == 0 && axes[2] == 2; }
};

/// A_n(x), passive (5.8, 5.9).
template <class T> mat3<T> elementary_rotation(int n, T x) {
    using std::cos;
    using std::sin;
    const int u = (n + 1) % 3, v = (n + 2) % 3;
    mat3<T> m = mat3<T>::Identity();
    m(u, u) = m(v, v) = cos(x);
    m(u, v) = sin(x);
    m(v, u) = -sin(x);
    return m;
}

/// A = A_c(γ) A_b(β) A_a(α)
template <class T> mat3<T> sequence_matrix(const euler_sequence& s, const std::array<T, 3>& q) {
    return elementary_rotation(s.axes[2], q[2]) * elementary_rotation(s.axes[1], q[1]) *
           elementary_rotation(s.axes[0], q[0]);
}

/// q = q_a(α) ⊗ q_b(β) ⊗ q_c(γ), w >= 0.
template <class T>
Eigen::Quaternion<T> sequence_quaternion(const euler_sequence& s, const std::array<T, 3>& q) {
    using std::cos;
    using std::sin;
    Eigen::Quaternion<T> r(T(1), T(0), T(0), T(0));
    for (int i = 0; i < 3; ++i) {
        Eigen::Quaternion<T> e(cos(q[i] / T(2)), T(0), T(0), T(0));
        e.coeffs()[s.axes[i]] = sin(q[i] / T(2)); // coeffs() = (x, y, z, w)
        r = r * e;
    }
    if (r.w() < T(0)) r.coeffs() = -r.coeffs();
    return r;
}

/// The distance from the singular set: |sin β| (proper Euler) or |cos β| (Tait–Bryan).
template <class T> T sequence_chart_distance(const euler_sequence& s, T beta) {
    using std::abs;
    using std::cos;
    using std::sin;
    return s.proper() ? abs(sin(beta)) : abs(cos(beta));
}

/// The angles of a passive matrix A. With R = Aᵀ = R_a(α) R_b(β) R_c(γ), ε = parity(), d = other():
///   proper:      β = atan2(hypot(R_ab, R_ad), R_aa), α = atan2(R_ba, −ε R_da),
///                γ = atan2(R_ab, ε R_ad);
///   Tait–Bryan:  β = atan2(ε R_ac, hypot(R_aa, R_ab)), α = atan2(−ε R_bc, R_cc),
///                γ = atan2(−ε R_ab, R_aa).
/// At the singularity (distance <= 4 eps) γ = 0 and α is the angle of R R_b(β)ᵀ = R_a(α).
template <class T>
std::array<T, 3> sequence_angles_from_matrix(const euler_sequence& s, const mat3<T>& A) {
    using std::atan2;
    using std::hypot;
    const mat3<T> R = A.transpose();
    const int a = s.axes[0], b = s.axes[1], c = s.axes[2], d = s.other();
    const T eps = std::numeric_limits<T>::epsilon(), e = T(s.parity());
    std::array<T, 3> q{};
    T dist;
    if (s.proper()) {
        dist = hypot(R(a, b), R(a, d));
        q[1] = atan2(dist, R(a, a));
        q[0] = atan2(R(b, a), -e * R(d, a));
        q[2] = atan2(R(a, b), e * R(a, d));
    } else {
        dist = hypot(R(a, a), R(a, b));
        q[1] = atan2(e * R(a, c), dist);
        q[0] = atan2(-e * R(b, c), R(c, c));
        q[2] = atan2(-e * R(a, b), R(a, a));
    }
    if (dist <= T(4) * eps) {
        if (s.proper())
            q[1] = R(a, a) > T(0) ? T(0) : T(EIGEN_PI);
        else
            q[1] = e * R(a, c) > T(0) ? T(EIGEN_PI) / T(2) : -T(EIGEN_PI) / T(2);
        const mat3<T> M = R * elementary_rotation(b, q[1]); // R R_b(β)ᵀ = R A_b(β)
        const int u = (a + 1) % 3, v = (a + 2) % 3;
        q[0] = atan2(M(v, u), M(u, u));
        q[2] = T(0);
    }
    if (s.proper()) {
        q[0] = detail::wrap_two_pi(q[0]);
        q[2] = detail::wrap_two_pi(q[2]);
    }
    return q;
}

/// The angles (α, β, γ) of sequence s of the attitude quaternion q (scalar first, active,
/// R(q) = Aᵀ), through the passive matrix A; ranges and the singular case as for
/// sequence_angles_from_matrix.
template <class T>
std::array<T, 3> sequence_angles_from_quaternion(const euler_sequence& s,
                                                 const Eigen::Quaternion<T>& q) {
    return sequence_angles_from_matrix(s, matrix_from_quaternion(q));
}

/// J with ω = J q̇ (body ω): columns A_c(γ) A_b(β) e_a, A_c(γ) e_b, e_c.
template <class T>
mat3<T> sequence_omega_jacobian(const euler_sequence& s, const std::array<T, 3>& q) {
    const mat3<T> Ac = elementary_rotation(s.axes[2], q[2]);
    const mat3<T> AcAb = Ac * elementary_rotation(s.axes[1], q[1]);
    mat3<T> J;
    J.col(0) = AcAb.col(s.axes[0]);
    J.col(1) = Ac.col(s.axes[1]);
    J.col(2) = mat3<T>::Identity().col(s.axes[2]);
    return J;
}

} // namespace rotgen
