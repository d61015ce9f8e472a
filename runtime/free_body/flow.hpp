/// \file
/// rotgen runtime — the exact flow of the free rigid body: body angular momentum m and attitude q
/// after a time h, in closed form (Jacobi elliptic functions and the incomplete elliptic integral
/// of the third kind). Needs Boost.Math (header-only), like exact_free_top.hpp.
///
///   free_body_flow<double> flow({I1, I2, I3});    principal moments along the body axes, > 0
///   flow.advance(q, m, h);                        (q, m) at t → (q, m) at t + h
///
/// Conventions (rotation.hpp): q is the unit quaternion of the ACTIVE rotation R(q) carrying body
/// to space coordinates (the passive matrix of the chapter is A = R(q)ᵀ, (5.25)); m = I ω is the
/// angular momentum in body axes, ω the body angular velocity (5.30); q̇ = ½ q ⊗ (0, ω) and Euler's
/// equations (5.87)–(5.89), ṁ = m × ω. The flow conserves T = ½ m·ω, G = |m| and the space momentum
/// R m exactly (to rounding).
///
/// Momentum (sorted frame I1 < I2 < I3; detail::free_body_momentum below): the elliptic solution of
/// exact_free_top.hpp (Landau & Lifshitz §37), with the parameter's complement mc formed directly
/// from the invariants, mc = (j3 − j1)(2T j2 − G²)/((j2 − j1)(2T j3 − G²)), never as 1 − k²
/// (Leroy, "Celledoni.tex" in the Principia project's documentation, corrections to Celledoni et
/// al. 2008). The polhode circles the axis whose component is the dn term and never changes sign
/// (axis 1 when G² < 2T I2, axis 3 when G² > 2T I2).
///
/// Attitude: let e = ±(that axis) with m·e > 0 at all times, u = m/G, and P(t) the shortest-arc
/// rotation taking u(t) to e (quaternion p = (1 + u·e, u × e)/norm, regular since u·e > 0: the
/// robust choice of Leroy's notes). R(t) m(t) = R0 m0 is constant, so S(t) = R(t) P(t)ᵀ keeps e
/// fixed: S(t) = S(0) Rot_e(ψ(t)) and
///   R(t) = R0 P0ᵀ Rot_e(ψ(t)) P(t),                  q(t) = q0 ⊗ p0* ⊗ q_e(ψ) ⊗ p(t).
/// Sᵀ Ṡ = [Pω]× + P Ṗᵀ gives ψ̇ = e·Pω − e·Ω_P, Ω_P = 2 vec(ṗ ⊗ p*); with e·Pω = u·ω = 2T/G,
/// e·Ω_P = e·(u × u̇)/(1 + u·e) and u × u̇ = (2T m − G² ω)/G² (Euler), writing x = m·e = A dn(u):
///   ψ̇ = 2T/G + Δ_e/(I_e G) · x/(G + x),            Δ_e = G² − 2T I_e = Σ_i m_i² (I_i − I_e)/I_i.
/// With u = λt + u0 and x/(G + x) = 1 − G/(G + A dn):
///   ψ(t) = 2T t/G + Δ_e/(I_e G) · (t − (W(u(t)) − W(u0))/λ),  W(u) = ∫₀ᵘ G du'/(G + A dn u'),
///   W(u) = (G²/c) Π(am u; −d/c | m) − G A/sqrt(c (c + d)) · atan(sqrt((c + d)/c) tan am u),
/// c = G² − A² (the transverse momentum squared where dn = 1), d = A² m, obtained by
/// rationalising G/(G + A dn) = G (G − A dn)/(c + d sn²) and dn du = d(am u). W is continued
/// over half periods by W(2Kj + r) = j W(2K) + W(r); for m <= 0.03 (a spin near a principal axis)
/// W and F are power series in m instead (small_parameter.hpp: about half the cost). Every case is
/// checked against DOP853 at rtol 1e-14 in tests/runtime/test_free_body.cpp (the published formulas
/// carry sign errors).
///
/// Special cases, where the general formulas divide by moment differences or by c: the sphere and
/// the symmetric top (two equal moments, the distinct one I_d along axis a): T = G²/(2 I_s) +
/// m_a²/2 (1/I_d − 1/I_s) splits into two commuting flows, a rotation about m by G t/I_s and one
/// about the body axis a by β t, β = m_a (I_s − I_d)/(I_s I_d):
///   q(t) = q0 ⊗ q_(m0/G)(G t/I_s) ⊗ q_a(β t),   m(t) = Rot_a(−β t) m0;
/// and a spin about a principal axis (two components of m exactly zero): q(t) = q0 ⊗ q_ω(|ω| t).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cmath>

#include "momentum.hpp"

namespace rotgen {

/// The exact flow of the free rigid body with principal moments I1, I2, I3 (body axes principal):
/// advance() carries the attitude q (unit quaternion, active, body → space) and the body angular
/// momentum m over a time h (the formulas in the file's comment).
template <class T> class free_body_flow {
  public:
    using vec3 = Eigen::Matrix<T, 3, 1>; ///< a 3-vector of body-axis components
    using quat = Eigen::Quaternion<T>;   ///< a quaternion (scalar first)

    /// The flow of the body with principal moments `inertia` (> 0, along the body axes).
    explicit free_body_flow(const std::array<T, 3>& inertia) : m_inertia(inertia) {}

    /// The principal moments I1, I2, I3.
    const std::array<T, 3>& inertia() const { return m_inertia; }

    /// (q, m) at t → (q, m) at t + h. q stays a unit quaternion (renormalised).
    void advance(quat& q, vec3& m, T h) const {
        const std::array<T, 3>& in = m_inertia;
        const int distinct = detail::distinct_axis(in);
        if (distinct >= 0 || detail::on_principal_axis(m)) {
            symmetric(q, m, h, distinct);
        } else {
            const detail::free_body_momentum<T> motion(in, {m[0], m[1], m[2]});
            general(q, m, h, motion);
        }
        q.normalize();
    }

  private:
    static quat axis_angle(const vec3& axis, T angle) {
        using std::cos;
        using std::sin;
        const T s = sin(angle / T(2));
        return quat(cos(angle / T(2)), axis[0] * s, axis[1] * s, axis[2] * s);
    }

    /// The shortest-arc rotation taking m/G to e (m·e > 0).
    static quat to_axis(const vec3& m, T g, const vec3& e) {
        const vec3 u = m / g;
        const vec3 v = u.cross(e);
        quat p(T(1) + u.dot(e), v[0], v[1], v[2]);
        p.normalize();
        return p;
    }

    /// |m| = G is an invariant; the elliptic formulas keep it to a few eps per call only, and a
    /// splitting run of many calls drifts in G and hence in the spin rate: 1.6e-10 rad after 3e4
    /// calls at spin 100 (asymmetric heavy top), 6.2e-11 with this correction (1.4e-11 and 1.5e-12
    /// with a larger nutation). The dn component is set from G² and the other two, where it
    /// dominates (m_a² > G²/2: the square root is then well conditioned).
    static void keep_norm(vec3& m, T g2, int a) {
        using std::sqrt;
        const T axis2 = m[a] * m[a];
        if (!(axis2 > g2 / T(2))) return;
        const T rest = m.squaredNorm() - axis2;
        m[a] = (m[a] >= T(0) ? T(1) : T(-1)) * sqrt(g2 - rest);
    }

    /// Sphere, symmetric top, or a spin about a principal axis (see the file comment).
    void symmetric(quat& q, vec3& m, T h, int distinct) const {
        const T g = m.norm();
        if (g == T(0)) return;
        if (distinct < 0) { // a spin about a principal axis
            const vec3 w(m[0] / m_inertia[0], m[1] / m_inertia[1], m[2] / m_inertia[2]);
            q = q * axis_angle(w / w.norm(), w.norm() * h);
            return;
        }
        const int a = distinct < 0 ? 0 : distinct;
        const T i_d = m_inertia[static_cast<std::size_t>(a)];
        const T i_s = m_inertia[static_cast<std::size_t>((a + 1) % 3)];
        const T beta = m[a] * (i_s - i_d) / (i_s * i_d);
        const vec3 e = vec3::Unit(a);
        q = q * axis_angle(m / g, g * h / i_s) * axis_angle(e, beta * h);
        m = axis_angle(e, -beta * h) * m;
    }

    void general(quat& q, vec3& m, T h, const detail::free_body_momentum<T>& motion) const {
        const T g = motion.g();
        const vec3 e = T(motion.axis_sign()) * vec3::Unit(motion.axis());
        const quat p0 = to_axis(m, g, e);
        const T g2 = m.squaredNorm();
        const auto end = motion.at(h);
        m = vec3(end.m[0], end.m[1], end.m[2]);
        keep_norm(m, g2, motion.axis());
        const T psi = motion.precession(h, end);
        q = q * p0.conjugate() * axis_angle(e, psi) * to_axis(m, g, e);
    }

    std::array<T, 3> m_inertia;
};

} // namespace rotgen
