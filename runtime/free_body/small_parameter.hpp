/// \file
/// rotgen runtime — the free body's phase integrals for a small parameter m = k² as power series in
/// m: F(φ | m) and the attitude's W (flow.hpp) without Carlson's R_F and R_J. A fast spin close to
/// a principal axis (a spinning top, a spin-stabilised satellite) has m of 1e-12 .. 1e-3, where two
/// or three terms reach rounding; elsewhere (m > small_parameter_limit) momentum.hpp keeps the
/// Carlson forms.
///
/// With φ = am u, du = dφ/Δ and dn u = Δ = sqrt(1 − m sin²φ) (A&S 16.1.5, 17.2.2), x = m sin²φ:
///   F(φ | m) = ∫₀^φ dθ/Δ = Σ_i c_i m^i S_i(φ),        c_i = C(2i, i)/4^i   ((1 − x)^(−1/2))
///   W(u) = ∫₀ᵘ G du'/(G + A dn u') = G/(G + A) ∫₀^φ f(m sin²θ) dθ = G/(G + A) Σ_i b_i m^i S_i(φ),
///   f(x) = 1/((1 − r (1 − sqrt(1 − x))) sqrt(1 − x)),  r = A/(G + A) ∈ (0, 1/2]
/// (G + A Δ = (G + A)(1 − r(1 − Δ))), b_i the Taylor coefficients of f, formed at run time by
/// series arithmetic from those of sqrt(1 − x), a_i = a_(i−1) (i − 3/2)/i. f is analytic for
/// |x| < 1 (1 − r(1 − Δ) >= 1 − r > 0 there), so b_i m^i falls like m^i; terms are kept while
/// m^i > 1e-18.
///   S_i(φ) = ∫₀^φ sin^(2i)θ dθ = (2i − 1)/(2i) S_(i−1) − sin^(2i−1)φ cos φ/(2i),   S_0 = φ
/// (the reduction formula, G&R 2.511.2), evaluated at the reduced amplitude ρ ∈ [−π/2, π/2] of
/// φ = jπ + ρ, with S_i(jπ + ρ) = j S_i(π) + S_i(ρ) and S_i(π) = π Π_(k<=i) (2k − 1)/(2k).
#pragma once

#include <boost/math/constants/constants.hpp>

#include <array>
#include <cmath>

namespace rotgen::detail {

template <class T> constexpr T small_parameter_limit = T(0.03); // 0.03^12 = 5e-19

template <class T> class phase_series {
  public:
    static constexpr int max_terms = 13;

    /// m = k², G = |m_body|, A = the dn term's amplitude of the momentum (0 < A <= G).
    phase_series(T m, T g, T a) {
        const T r = a / (g + a);
        std::array<T, max_terms> sq{}, p{}, f{};
        sq[0] = T(1);
        T mi = T(1), c = T(1);
        m_terms = 1;
        m_f[0] = T(1);
        for (int i = 1; i < max_terms && mi * m > T(1e-18); ++i, ++m_terms) {
            mi *= m;
            sq[i] = sq[i - 1] * (T(i) - T(1.5)) / T(i);
            c *= T(2 * i - 1) / T(2 * i);
            m_f[i] = c * mi;
        }
        // p = (1 − r (1 − sqrt)) · sqrt, then f = 1/p (p_0 = 1)
        for (int i = 0; i < m_terms; ++i)
            for (int k = 0; k <= i; ++k)
                p[i] += (k == 0 ? T(1) : r * sq[k]) * sq[i - k];
        mi = T(1);
        for (int i = 0; i < m_terms; ++i, mi *= m) {
            T s = i == 0 ? T(1) : T(0);
            for (int k = 1; k <= i; ++k)
                s -= p[k] * f[i - k];
            f[i] = s;
            m_w[i] = g / (g + a) * f[i] * mi;
        }
    }

    struct sums {
        T f, w;
    };
    /// F and W at φ = jπ + ρ, |ρ| <= π/2.
    sums at(long long j, T rho) const {
        using std::cos;
        using std::sin;
        const T s = sin(rho), c = cos(rho), pi = boost::math::constants::pi<T>();
        T si = rho, period = pi, s_pow = s; // S_0(ρ), S_0(π), sin^(2i−1)
        sums out{m_f[0] * (si + T(j) * period), m_w[0] * (si + T(j) * period)};
        for (int i = 1; i < m_terms; ++i) {
            const T q = T(2 * i - 1) / T(2 * i);
            si = q * si - s_pow * c / T(2 * i);
            period *= q;
            s_pow *= s * s;
            out.f += m_f[i] * (si + T(j) * period);
            out.w += m_w[i] * (si + T(j) * period);
        }
        return out;
    }

  private:
    std::array<T, max_terms> m_f{}, m_w{}; ///< c_i m^i and G/(G + A) b_i m^i
    int m_terms = 0;
};

} // namespace rotgen::detail
