/// \file
/// rotgen runtime — the exact solution of the force-free asymmetric top, omega(t) in body axes,
/// in Jacobi elliptic functions (Boost.Math). A reference for tests and benchmarks: Euler's
/// equations (5.87)-(5.89), I1 omega1' = (I2 - I3) omega2 omega3 and cyclic permutations.
#pragma once

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>

#include <array>
#include <cmath>
#include <stdexcept>

namespace rotgen {

/// Exact solution (Landau & Lifshitz, Mechanics, §37), for I1 < I2 < I3 off the separatrix.
/// Invariants: 2E = Σ I_i ω_i²,  L² = Σ I_i² ω_i²,  and I1 <= L²/(2E) <= I3.
/// Eliminating ω1 and ω3 with the invariants,
///   I1 (I3 − I1) ω1² = (2E I3 − L²) − I2 (I3 − I2) ω2²
///   I3 (I3 − I1) ω3² = (L² − 2E I1) − I2 (I2 − I1) ω2²
/// so that ω2' = (I3 − I1)/I2 · ω3 ω1 is a separable equation solved by elliptic functions.
/// Case L² < 2E·I2 (the polhode circles the axis of the smallest moment, ω1 never vanishes):
///   ω1 = s1 A1 dn(u, k),  ω2 = σ A2 sn(u, k),  ω3 = A3 cn(u, k),  u = λ t + u0,
///   A1² = (2E I3 − L²) / (I1 (I3 − I1)),   A2² = (L² − 2E I1) / (I2 (I2 − I1)),
///   A3² = (L² − 2E I1) / (I3 (I3 − I1)),   λ² = (I2 − I1)(2E I3 − L²) / (I1 I2 I3),
///   k²  = (I3 − I2)(L² − 2E I1) / ((I2 − I1)(2E I3 − L²))  (< 1 exactly when L² < 2E I2).
/// Substituting (sn' = cn dn, cn' = −sn dn, dn' = −k² sn cn) into the three equations gives the
/// identities A2 λ = |I3 − I1|/I2 A1 A3, A1 λ k² = |I3 − I2|/I1 A2 A3, A3 λ = |I2 − I1|/I3 A1 A2
/// and the sign condition σ = s1 · sgn(I3 − I1); s1 = sgn ω1(0). The phase u0 = F(φ0, k) with
/// the amplitude φ0 = atan2(sn u0, cn u0) = atan2(ω2(0)/(σ A2), ω3(0)/A3).
/// Case L² > 2E·I2 (about the axis of the largest moment, ω3 never vanishes): relabel the axes
/// 1 ↔ 3 and flip the sign of ω2 — (I1, I2, I3) → (I3, I2, I1), (ω1, ω2, ω3) → (ω3, −ω2, ω1) maps
/// Euler's equations onto themselves — and use the formulas above in the relabelled frame (where
/// I3 − I1 < 0, hence σ = −s1, and every quantity under a square root is again positive).
/// The constructor throws std::invalid_argument for moments out of order or a state on the
/// separatrix (L² = 2E·I2).
template <class T> class free_top_exact {
  public:
    /// Solves for the amplitudes, λ, k and the phase from the principal moments I (I1 < I2 < I3)
    /// and ω(0) = w0 in body axes.
    free_top_exact(std::array<T, 3> I, std::array<T, 3> w0) {
        using std::sqrt;
        if (!(I[0] < I[1] && I[1] < I[2]))
            throw std::invalid_argument("free_top_exact: needs I1 < I2 < I3");
        m_e2 = I[0] * w0[0] * w0[0] + I[1] * w0[1] * w0[1] + I[2] * w0[2] * w0[2];
        m_l2 =
            I[0] * I[0] * w0[0] * w0[0] + I[1] * I[1] * w0[1] * w0[1] + I[2] * I[2] * w0[2] * w0[2];
        if (m_l2 == m_e2 * I[1])
            throw std::invalid_argument("free_top_exact: the state is on the separatrix");
        m_flip = m_l2 > m_e2 * I[1];
        std::array<T, 3> j = I, v = w0;
        if (m_flip) {
            j = {I[2], I[1], I[0]};
            v = {w0[2], -w0[1], w0[0]};
        }
        // 2E I3 - L^2 and L^2 - 2E I1 without cancellation (they are small differences of large
        // numbers when the moments span many orders of magnitude):
        //   2E I_k - L^2 = sum_i I_i (I_k - I_i) omega_i^2.
        T high = 0, low = 0; // 2E j3 - L^2, L^2 - 2E j1
        for (int i = 0; i < 3; ++i) {
            high += j[i] * (j[2] - j[i]) * v[i] * v[i];
            low += j[i] * (j[i] - j[0]) * v[i] * v[i];
        }
        m_a1 = sqrt(high / (j[0] * (j[2] - j[0])));
        m_a2 = sqrt(low / (j[1] * (j[1] - j[0])));
        m_a3 = sqrt(low / (j[2] * (j[2] - j[0])));
        m_lambda = sqrt((j[1] - j[0]) * high / (j[0] * j[1] * j[2]));
        m_k = sqrt((j[2] - j[1]) * low / ((j[1] - j[0]) * high));
        m_s1 = v[0] >= T(0) ? T(1) : T(-1);
        m_sigma = m_s1 * (j[2] > j[0] ? T(1) : T(-1));
        using std::atan2;
        const T amplitude = atan2(v[1] / (m_sigma * m_a2), v[2] / m_a3);
        m_u0 = boost::math::ellint_1(m_k, amplitude);
    }

    /// ω(t) in body axes, t in the units of the moments and ω(0).
    std::array<T, 3> operator()(T t) const {
        T cn, dn;
        const T sn = boost::math::jacobi_elliptic(m_k, m_lambda * t + m_u0, &cn, &dn);
        const std::array<T, 3> v = {m_s1 * m_a1 * dn, m_sigma * m_a2 * sn, m_a3 * cn};
        if (m_flip) return {v[2], -v[1], v[0]};
        return v;
    }

    /// The modulus k of the Jacobi elliptic functions (k² < 1).
    T modulus() const { return m_k; }
    /// period of the motion of ω: 4K(k)/λ
    T period() const { return T(4) * boost::math::ellint_1(m_k) / m_lambda; }

  private:
    T m_e2, m_l2, m_a1, m_a2, m_a3, m_lambda, m_k, m_u0, m_s1, m_sigma;
    bool m_flip;
};

} // namespace rotgen
