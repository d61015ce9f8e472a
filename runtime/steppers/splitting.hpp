/// \file
/// rotgen runtime — splitting methods on the exact free rigid-body flow: split2, split4, split6.
///
/// H = T(m) + V(q, t): the free body T = ½ Σ m_i²/I_i moves exactly (free_body/flow.hpp) and the
/// potential acts as kicks that change the body momentum at a fixed attitude, m ← m + a h τ(t, q)
/// (McLachlan 1993; Touma & Wisdom 1994; Dullweber, Leimkuhler & McLachlan 1997; Celledoni, Fassò,
/// Säfström & Zanna 2008). Both parts are exact Hamiltonian flows, so every method here is
/// symplectic and conserves the space angular momentum about any axis of symmetry of V (p_φ of
/// the heavy top) to rounding; the energy error stays bounded, without drift.
///
///   split2   Strang: S(h) = K(h/2) ∘ F(h) ∘ K(h/2); second order, time-reversible
///   split4   Suzuki's five-stage symmetric composition of S, 4th order:
///            S(p h) S(p h) S((1 − 4p) h) S(p h) S(p h),  p = 1/(4 − 4^(1/3))
///            (M. Suzuki, Phys. Lett. A 146 (1990) 319, eq. (3.13); closed form, no digits copied)
///   split6   Yoshida's seven-stage symmetric composition of S, 6th order ("solution A"),
///            γ1 = γ7 = 0.78451361047755726381949763, γ2 = γ6 = 0.23557321335935813368479318,
///            γ3 = γ5 = −1.17767998417887100694641568, γ4 = 1 − 2(γ1 + γ2 + γ3)
///            (H. Yoshida, Phys. Lett. A 150 (1990) 262, Table 1; the digits as printed in Hairer,
///            Lubich & Wanner, Geometric Numerical Integration, 2nd ed., §V.3.2, eq. (3.11))
/// Consecutive half kicks of neighbouring stages are merged (one torque evaluation between two
/// free flows). A time-dependent torque is evaluated at the time the free flows have reached
/// (t is advanced by the free part: the splitting of the autonomous extended system).
///
/// Fixed step h (`step`); the driver's grid (integrate/fixed.hpp) shortens the last step. Samples
/// inside a step are the method itself run from the step's start by θh (continuous extension of
/// order p; events are located on it). step_stats::rhs_evals counts torque evaluations (kicks).
/// The same methods under error control (rtol, atol): steppers/split_doubling.hpp.
/// Stepper concept (stepper.hpp): order 2/4/6, no error estimate, continuous extension, no
/// Jacobian. Needs a split system (split_system.hpp) and Boost.Math (through free_body/flow.hpp).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include "../combine.hpp"
#include "../free_body/flow.hpp"
#include "../split_system.hpp"
#include "../stepper.hpp"

namespace rotgen {

namespace detail {
/// The stage coefficients γ of the symmetric compositions above.
template <class T, int Order> struct split_coefficients;
template <class T> struct split_coefficients<T, 2> {
    static std::array<T, 1> gamma() { return {T(1)}; }
};
template <class T> struct split_coefficients<T, 4> {
    static std::array<T, 5> gamma() {
        using std::cbrt;
        const T p = T(1) / (T(4) - cbrt(T(4))); // Suzuki (1990)
        return {p, p, T(1) - T(4) * p, p, p};
    }
};
template <class T> struct split_coefficients<T, 6> {
    static std::array<T, 7> gamma() { // Yoshida (1990), solution A
        const T g1 = T(0.78451361047755726381949763L), g2 = T(0.23557321335935813368479318L),
                g3 = T(-1.17767998417887100694641568L);
        const T g4 = T(1) - T(2) * (g1 + g2 + g3);
        return {g1, g2, g3, g4, g3, g2, g1};
    }
};
} // namespace detail

template <class T, class S, int Order> class split_stepper;

/// Options of the fixed-step splitting method of order Order (2, 4 or 6; the file's comment): a
/// step and a step budget.
template <class T, int Order> struct split_method {
    static_assert(Order == 2 || Order == 4 || Order == 6, "split methods of order 2, 4, 6");
    /// The floating-point type of the run.
    using scalar = T;
    /// Marks a method the driver accepts (stepper.hpp).
    static constexpr bool is_rotgen_method = true;
    /// Fixed step: the options are `step` and `max_steps`; no error estimate.
    static constexpr bool adaptive = false;
    /// Runs only on a split system (split_system.hpp).
    static constexpr bool needs_split_system = true;
    /// The stepper for a system of type S.
    template <class S> using stepper = split_stepper<T, S, Order>;

    T step = T(0);                     ///< step size h > 0
    std::size_t max_steps = 100000000; ///< step budget

    /// The method's name, as scene files and `rotgen simulate` spell it.
    std::string name() const { return "split" + std::to_string(Order); }
    /// An empty string when the options are valid, else the reason (one line).
    std::string check() const {
        using std::isfinite;
        return step > T(0) && isfinite(step) ? "" : "step must be finite and > 0";
    }
};

/// Strang splitting, 2nd order (fixed step).
template <class T> using split2 = split_method<T, 2>;
/// Suzuki's composition, 4th order (fixed step).
template <class T> using split4 = split_method<T, 4>;
/// Yoshida's composition, 6th order (fixed step).
template <class T> using split6 = split_method<T, 6>;

/// The splitting method's working storage for one split system type S (the stepper concept of
/// stepper.hpp): kicks by the torque between exact free-body flows (free_body/flow.hpp).
template <class T, class S, int Order> class split_stepper {
  public:
    /// The floating-point type of the run.
    using scalar = T;
    /// The system type S this stepper integrates.
    using system_type = S;
    /// The state vector of S.
    using vector = state_vector<T, S>;

    /// Order p of the step: local error O(h^(p+1)).
    static constexpr int order = Order;
    /// No error estimate: attempt() returns err = 0.
    static constexpr bool error_estimate = false;
    /// Samples inside a step come from the stepper's own interpolant, dense().
    static constexpr dense_kind dense_output = dense_kind::continuous_extension;
    /// Order of the interpolant (local error O(h^(dense_order+1))).
    static constexpr int dense_order = Order;
    /// Never evaluates ∂f/∂y.
    static constexpr bool uses_jacobian = false;

    /// Storage for n state components (the options hold nothing the stepper needs).
    split_stepper(const split_method<T, Order>&, std::size_t n)
        : m_y0(detail::make_work_vector<vector>(n)), m_y1(m_y0), m_f(m_y0) {}

    /// f(t0, y0), after start() (for the initial step selection).
    const vector& f_start() const { return m_f; }
    /// The state at t + h of the last attempt().
    const vector& y_new() const { return m_y1; }

    /// Begins a run at (t0, y0): evaluates f(t0, y0); false when it is not finite.
    bool start(const S& sys, T t0, const vector& y0, step_stats& stats) {
        static_assert(has_split_interface_v<S, T>,
                      "the split methods need a split system: principal_moments() and "
                      "torque(t, y, tau) (split_system.hpp)");
        detail::eval_rhs(sys, t0, y0, m_f, stats);
        return detail::all_finite(m_f);
    }

    /// One step of size h from (t, y) into y_new(); code ok or non_finite, err 0 (no estimate).
    step_outcome<T> attempt(const S& sys, T t, const vector& y, T h, step_stats& stats,
                            bool need_dense) {
        advance(sys, t, y, h, m_y1, stats);
        if (need_dense) {
            m_sys = &sys;
            m_t = t;
            m_h = h;
            m_y0 = y;
        }
        return {detail::all_finite(m_y1) ? status::ok : status::non_finite, T(0)};
    }

    /// Nothing to prepare (samples are the method run from the step's start): always true.
    bool accept(const S&, step_stats&, bool) { return true; }

    /// The state at t + θh: the method run from the step's start with the step θh.
    void dense(T theta, vector& out) const {
        step_stats unused;
        advance(*m_sys, m_t, m_y0, theta * m_h, out, unused);
    }

    /// One step of the composition from (t, y) by h into out. A system whose body axes are not
    /// principal (split_system.hpp) is moved in the principal frame: q ⊗ p and Pᵀ ω in, back out.
    static void advance(const S& sys, T t, const vector& y, T h, vector& out, step_stats& stats) {
        using vec3 = Eigen::Matrix<T, 3, 1>;
        const std::array<T, 3> in = sys.principal_moments();
        const free_body_flow<T> flow(in);
        const Eigen::Quaternion<T> p = axes_of(sys);
        const bool rotated = p.w() != T(1);
        Eigen::Quaternion<T> q(y[0], y[1], y[2], y[3]);
        vec3 w(y[4], y[5], y[6]);
        if (rotated) q = q * p, w = p.conjugate() * w;
        vec3 m(in[0] * w[0], in[1] * w[1], in[2] * w[2]);
        const auto g = detail::split_coefficients<T, Order>::gamma();
        T tk = t;
        kick(sys, tk, q, m, g[0] * h / T(2), p, rotated, stats);
        for (std::size_t i = 0; i < g.size(); ++i) {
            flow.advance(q, m, g[i] * h);
            tk = i + 1 == g.size() ? t + h : tk + g[i] * h;
            const T a = i + 1 < g.size() ? (g[i] + g[i + 1]) / T(2) : g[i] / T(2);
            kick(sys, tk, q, m, a * h, p, rotated, stats);
        }
        for (int i = 0; i < 3; ++i)
            w[i] = m[i] / in[static_cast<std::size_t>(i)];
        if (rotated) q = q * p.conjugate(), w = p * w;
        out[0] = q.w(), out[1] = q.x(), out[2] = q.y(), out[3] = q.z();
        for (int i = 0; i < 3; ++i)
            out[4 + i] = w[i];
    }

  private:
    /// The quaternion p of the principal axes (identity when the body axes are principal).
    static Eigen::Quaternion<T> axes_of(const S& sys) {
        if constexpr (has_principal_axes_v<S>) {
            const auto& a = sys.principal_axes();
            return Eigen::Quaternion<T>(T(a[0]), T(a[1]), T(a[2]), T(a[3]));
        } else {
            return Eigen::Quaternion<T>::Identity();
        }
    }

    /// m ← m + dt τ(t, q): the exact flow of the potential for a time dt (q does not move); in the
    /// principal frame (rotated) the torque is taken at the body attitude q ⊗ p* and τ_p = Pᵀ τ.
    template <class Q, class M>
    static void kick(const S& sys, T t, const Q& q, M& m, T dt, const Eigen::Quaternion<T>& p,
                     bool rotated, step_stats& stats) {
        const Q qb = rotated ? Q(q * p.conjugate()) : q;
        const T yq[7] = {qb.w(), qb.x(), qb.y(), qb.z(), T(0), T(0), T(0)};
        T tau[3];
        sys.torque(t, yq, tau);
        ++stats.rhs_evals;
        Eigen::Matrix<T, 3, 1> tv(tau[0], tau[1], tau[2]);
        if (rotated) tv = p.conjugate() * tv;
        for (int i = 0; i < 3; ++i)
            m[i] += dt * tv[i];
    }

    vector m_y0, m_y1, m_f;
    const S* m_sys = nullptr;
    T m_t = T(0), m_h = T(0);
};

static_assert(check_method<split2<double>>());
static_assert(check_method<split6<double>>());

} // namespace rotgen
