/// \file
/// rotgen runtime — the Jacobi amplitude am(u | m), sn, cn, dn, and the incomplete elliptic
/// integrals the exact free rigid body needs, all from the parameter m = k² AND its complement
/// mc = 1 − m given separately.
///
/// Why not boost::math::jacobi_elliptic(k, u, …) and ellint_1/ellint_3(k, …): Boost takes the
/// modulus k and forms k' = sqrt(1 − k²) itself. Near the separatrix of the free body (k → 1) the
/// motion is governed by k', which is then known only to eps/k'² relative (mc = 1e-10: 1e-6).
/// The body's invariants give mc directly and without cancellation (flow.hpp), so everything here
/// takes mc as an input and never forms it from k.
///
/// am(u | m) by the arithmetic–geometric mean (Abramowitz & Stegun 16.4, the descending Gauss
/// transformation):
///   a0 = 1, b0 = sqrt(mc), c0 = sqrt(m);
///   a_{n+1} = (a_n + b_n)/2,  b_{n+1} = sqrt(a_n b_n),  c_{n+1} = (a_n − b_n)/2,  until c_N ~ 0;
///   φ_N = 2^N a_N u;  φ_{n−1} = (φ_n + asin(c_n sin φ_n / a_n))/2;  am(u) = φ_0;
///   K(m) = π / (2 a_N)                                                        (A&S 17.6.1)
/// u is first reduced to r ∈ [−K, K] with u = 2K j + r: am(u) = jπ + am(r) (A&S 16.8), so that
/// the rounding of φ_N does not grow with u. dn is then formed as sqrt(mc + m cos²φ) (a sum of two
/// non-negative terms: no cancellation, unlike 1 − m sin²φ). At mc = 0 (the separatrix, K = ∞)
/// am(u | 1) = gd(u) = atan(sinh u) (A&S 16.15).
///
/// Incomplete integrals in Carlson's symmetric forms (Boost.Math ellint_rf, ellint_rj; DLMF 19.25.5
/// and 19.25.14), for |φ| <= π/2, with s = sin φ, c = cos φ, Δ² = mc + m c²:
///   F(φ | m)    = s R_F(c², Δ², 1)
///   Π(φ; n | m) = s R_F(c², Δ², 1) + (n/3) s³ R_J(c², Δ², 1, 1 − n s²)    (Π with 1 − n sin²)
/// and the complete ones at φ = π/2 (c = 0, Δ² = mc). Where φ = am(r) came from the AGM, F(φ | m) =
/// r is known and only R_J is evaluated; the complete Π takes K from the AGM. (For m <= 0.03 the
/// free body uses the series of small_parameter.hpp instead.)
#pragma once

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>

#include <cmath>
#include <limits>

namespace rotgen::detail {

/// Boost.Math evaluates double in long double by default (x87, several times slower); the
/// Carlson algorithms are accurate in the working precision itself.
using carlson_policy = boost::math::policies::policy<boost::math::policies::promote_double<false>>;

/// sn, cn, dn at u and the amplitude am(u), unwrapped (continuous in u).
template <class T> struct jacobi_values {
    T am, sn, cn, dn;
    long long half_periods; ///< j in u = 2K j + r
    T reduced_am;           ///< am(r) ∈ [−π/2, π/2]
    T reduced_u;            ///< r = F(am(r) | m)
};

/// The AGM table of one parameter (m, mc), built once and used for every u.
template <class T> class jacobi_amplitude {
  public:
    static constexpr int max_levels = 40;

    jacobi_amplitude(T m, T mc) : m_m(m), m_mc(mc) {
        using std::abs;
        using std::sqrt;
        const T eps = std::numeric_limits<T>::epsilon();
        if (mc <= T(0)) { // the separatrix: K = ∞, am = gd
            m_k_complete = std::numeric_limits<T>::infinity();
            return;
        }
        T a = T(1), b = sqrt(mc), c = sqrt(m);
        m_a[0] = a;
        m_c[0] = c;
        while (abs(c) > eps * a && m_levels + 1 < max_levels) {
            const T an = (a + b) / T(2);
            c = (a - b) / T(2);
            b = sqrt(a * b);
            a = an;
            ++m_levels;
            m_a[m_levels] = a;
            m_c[m_levels] = c;
        }
        m_k_complete = boost::math::constants::pi<T>() / (T(2) * a);
    }

    T parameter() const { return m_m; }
    T complement() const { return m_mc; }
    T complete_k() const { return m_k_complete; } // K(m)

    jacobi_values<T> operator()(T u) const {
        using std::cos;
        using std::round;
        using std::sin;
        using std::sqrt;
        jacobi_values<T> v{};
        T r = u;
        if (m_mc > T(0)) {
            const T j = round(u / (T(2) * m_k_complete));
            v.half_periods = static_cast<long long>(j);
            r = u - T(2) * m_k_complete * j;
        }
        v.reduced_u = r;
        v.reduced_am = reduced(r);
        v.am = T(v.half_periods) * boost::math::constants::pi<T>() + v.reduced_am;
        const T sign = (v.half_periods % 2 == 0) ? T(1) : T(-1);
        const T c = cos(v.reduced_am);
        v.sn = sign * sin(v.reduced_am);
        v.cn = sign * c;
        v.dn = sqrt(m_mc + m_m * c * c);
        return v;
    }

  private:
    /// am(r) for |r| <= K (or any r at the separatrix).
    T reduced(T r) const {
        using std::atan;
        using std::ldexp;
        using std::sin;
        using std::sinh;
        if (m_mc <= T(0)) return atan(sinh(r));
        T phi = ldexp(m_a[m_levels] * r, m_levels);
        for (int n = m_levels; n > 0; --n)
            phi = (phi + small_asin(m_c[n] * sin(phi) / m_a[n])) / T(2);
        return phi;
    }

    /// asin x; the AGM's ratios c_n/a_n fall quadratically, so below the first level or two |x|
    /// is tiny and the series x (1 + x²/6 + 3x⁴/40 + 5x⁶/112) is exact to rounding (|x| < 1e-3:
    /// the next term, 35x⁹/1152, is below 1e-28).
    static T small_asin(T x) {
        using std::abs;
        using std::asin;
        if (abs(x) >= T(1e-3)) return asin(x);
        const T x2 = x * x;
        return x * (T(1) + x2 * (T(1) / T(6) + x2 * (T(3) / T(40) + x2 * (T(5) / T(112)))));
    }

    T m_m, m_mc;
    T m_a[max_levels] = {}, m_c[max_levels] = {};
    int m_levels = 0;
    T m_k_complete = T(0);
};

/// Π(φ; n | m) for |φ| <= π/2 given F = F(φ | m) (Π's integrand 1/((1 − n sin²) Δ)), n <= 0 here:
/// where φ = am(r) is known, F = r and only R_J is evaluated.
template <class T> T incomplete_pi(T n, T f, T s, T c, T delta2) {
    return f + n / T(3) * s * s * s *
                   boost::math::ellint_rj(c * c, delta2, T(1), T(1) - n * s * s, carlson_policy());
}

/// F(φ | m) and Π(φ; n | m) for |φ| <= π/2.
template <class T> struct incomplete_f_pi { T f, pi; };
template <class T> incomplete_f_pi<T> incomplete_integrals(T n, T s, T c, T delta2) {
    const T f = s * boost::math::ellint_rf(c * c, delta2, T(1), carlson_policy());
    return {f, incomplete_pi(n, f, s, c, delta2)};
}

/// Π(n | m), the complete integral (φ = π/2), from K(m) (the AGM's, jacobi_amplitude); mc > 0.
template <class T> T complete_pi(T n, T mc, T k_complete) {
    return k_complete +
           n / T(3) * boost::math::ellint_rj(T(0), mc, T(1), T(1) - n, carlson_policy());
}

} // namespace rotgen::detail
