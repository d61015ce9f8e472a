/// \file
/// rotgen runtime — the systems the splitting methods (steppers/splitting.hpp) run: a rigid body
/// whose principal axes are the body axes, moved by the torque of a potential (and torques given
/// as functions of time), with the body form's state layout (DESIGN.md, "State layouts")
///   y = (qw, qx, qy, qz, ω1, ω2, ω3),
/// q the unit quaternion of the active rotation body → space (rotation.hpp), ω the body angular
/// velocity (5.30). A split system S provides, besides rhs (system.hpp):
///   std::array<T, 3> principal_moments() const;      I1, I2, I3 along the body axes, > 0
///   void torque(T t, const T* y, T* tau) const;      body-axis torque at (t, q = y[0..3]); it must
///                                                    not depend on ω (a rate-dependent force is
///                                                    not a kick: those models need another method)
/// `split_body_system<T, Torque>` builds one from the moments and a torque callable
/// torque(t, y, tau); its rhs is the body form of the same model,
///   q̇ = ½ q ⊗ (0, ω),    I ω̇ = τ − ω × I ω                             (5.87)–(5.89) with τ,
/// so every other method runs the same system too (the tests compare them).
/// A split system may also provide
///   std::array<T, 4> principal_axes() const;         the unit quaternion p = (w, x, y, z) whose
///                                                    rotation P has the principal axes (body
///                                                    components) as columns: v_body = P
///                                                    v_principal
/// when its body axes are not principal (products of inertia, (5.39)); principal_moments() are
/// then the moments along P's columns and torque() stays in body axes. The split methods move the
/// body in the principal frame (steppers/splitting.hpp): attitude q ⊗ p (R(q) P carries principal
/// to space components), ω_p = Pᵀ ω, τ_p = Pᵀ τ (the inertia P D Pᵀ of (5.69) with A = Pᵀ).
/// `body_split_system<S>` makes a split system of any body-form system S (7 states, the layout
/// above: a generated model's body form, or the loaded kernels of `rotgen simulate`): at ω = 0 the
/// gyroscopic term vanishes, so the torque is τ = I ω̇(t, q, ω = 0), I the full inertia tensor in
/// body axes — valid when S's torque does not depend on ω (no damping), which the caller checks.
#pragma once

#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>

namespace rotgen {

namespace detail {
template <class S, class T, class = void> struct has_split_interface : std::false_type {};
template <class S, class T>
struct has_split_interface<
    S, T,
    std::void_t<decltype(std::declval<const S&>().principal_moments()[0]),
                decltype(std::declval<const S&>().torque(
                    std::declval<T>(), std::declval<const T*>(), std::declval<T*>()))>>
    : std::true_type {};
} // namespace detail

/// True when S can be run by the splitting methods.
template <class S, class T>
inline constexpr bool has_split_interface_v = detail::has_split_interface<S, T>::value;

namespace detail {
template <class S, class = void> struct has_principal_axes : std::false_type {};
template <class S>
struct has_principal_axes<S, std::void_t<decltype(std::declval<const S&>().principal_axes()[0])>>
    : std::true_type {};
} // namespace detail

/// True when S's body axes may differ from its principal axes (principal_axes() above).
template <class S>
inline constexpr bool has_principal_axes_v = detail::has_principal_axes<S>::value;

/// The torque of uniform gravity on a body whose centre of mass is r (body axes) from the fixed
/// point: τ = r × (−M g ê) = M g ê × r, ê the space vertical in body axes, ê = R(q)ᵀ e_z =
/// (2(xz − wy), 2(yz + wx), 1 − 2(x² + y²)); the potential is V = M g r·ê (M g h cos θ for
/// r = (0, 0, h), (5.73)). `mg_r` holds M g r.
template <class T> struct gravity_torque {
    std::array<T, 3> mg_r; ///< M g r: mass × gravitational acceleration × the centre of mass from
                           ///< the fixed point (body axes)
    /// τ at the attitude q = y[0..3] into tau (body axes).
    void operator()(T, const T* y, T* tau) const {
        const T e[3] = {T(2) * (y[1] * y[3] - y[0] * y[2]), T(2) * (y[2] * y[3] + y[0] * y[1]),
                        T(1) - T(2) * (y[1] * y[1] + y[2] * y[2])};
        tau[0] = e[1] * mg_r[2] - e[2] * mg_r[1];
        tau[1] = e[2] * mg_r[0] - e[0] * mg_r[2];
        tau[2] = e[0] * mg_r[1] - e[1] * mg_r[0];
    }
};

/// A split system (see the file's comment) of a body with principal moments along its body axes
/// and a torque callable torque(t, y, tau) that does not depend on ω; its rhs is the body form
/// (5.87)–(5.89) with τ, so every method can run it.
template <class T, class Torque> class split_body_system {
  public:
    static constexpr std::size_t state_size =
        7; ///< 7: the body form's (qw, qx, qy, qz, ω1, ω2, ω3)

    /// The body of principal moments I1, I2, I3 (> 0) and the torque.
    split_body_system(std::array<T, 3> moments, Torque torque)
        : m_moments(moments), m_torque(std::move(torque)) {}

    /// I1, I2, I3 along the body axes.
    const std::array<T, 3>& principal_moments() const { return m_moments; }
    /// The body-axis torque at (t, q = y[0..3]), into tau.
    void torque(T t, const T* y, T* tau) const { m_torque(t, y, tau); }

    /// The body form's dy/dt: q̇ = ½ q ⊗ (0, ω), I ω̇ = τ − ω × I ω.
    void rhs(T t, const T* y, T* d) const {
        const std::array<T, 3>& i = m_moments;
        const T* w = y + 4;
        T tau[3];
        m_torque(t, y, tau);
        d[0] = -(y[1] * w[0] + y[2] * w[1] + y[3] * w[2]) / T(2); // ½ q ⊗ (0, ω)
        d[1] = (y[0] * w[0] + y[2] * w[2] - y[3] * w[1]) / T(2);
        d[2] = (y[0] * w[1] + y[3] * w[0] - y[1] * w[2]) / T(2);
        d[3] = (y[0] * w[2] + y[1] * w[1] - y[2] * w[0]) / T(2);
        d[4] = (tau[0] + (i[1] - i[2]) * w[1] * w[2]) / i[0]; // (5.87)
        d[5] = (tau[1] + (i[2] - i[0]) * w[2] * w[0]) / i[1];
        d[6] = (tau[2] + (i[0] - i[1]) * w[0] * w[1]) / i[2];
    }

  private:
    std::array<T, 3> m_moments;
    Torque m_torque;
};

/// A split_body_system of the moments and the torque callable.
template <class T, class Torque>
split_body_system<T, Torque> make_split_system(std::array<T, 3> moments, Torque torque) {
    return split_body_system<T, Torque>(moments, std::move(torque));
}

/// A body-form system seen as a split system (see above); holds a reference to it.
template <class S> class body_split_system {
  public:
    std::size_t size() const { return 7; } ///< run-time size (7): works on Eigen::VectorXd states

    /// Principal body axes: the moments along them.
    body_split_system(const S& body, std::array<double, 3> moments)
        : m_body(body), m_moments(moments) {
        for (std::size_t i = 0; i < 3; ++i)
            m_tensor[i][i] = moments[i];
    }
    /// Any body axes: the tensor in body axes, its principal moments and the quaternion p of the
    /// axes (the file comment).
    body_split_system(const S& body, const std::array<std::array<double, 3>, 3>& tensor,
                      std::array<double, 3> moments, std::array<double, 4> axes)
        : m_body(body), m_moments(moments), m_tensor(tensor), m_axes(axes) {}

    /// The principal moments (of the full tensor).
    const std::array<double, 3>& principal_moments() const { return m_moments; }
    /// The unit quaternion p = (w, x, y, z) whose rotation has the principal axes as columns.
    const std::array<double, 4>& principal_axes() const { return m_axes; }
    /// The torque τ = I ω̇(t, q, ω = 0) of the body form, I the full tensor in body axes (valid when
    /// the body's torque does not depend on ω).
    void torque(double t, const double* y, double* tau) const {
        const double y0[7] = {y[0], y[1], y[2], y[3], 0.0, 0.0, 0.0};
        double d[7];
        m_body.rhs(t, y0, d);
        for (std::size_t i = 0; i < 3; ++i)
            tau[i] = m_tensor[i][0] * d[4] + m_tensor[i][1] * d[5] + m_tensor[i][2] * d[6];
    }
    /// The body form's own rhs.
    void rhs(double t, const double* y, double* dydt) const { m_body.rhs(t, y, dydt); }

  private:
    const S& m_body;
    std::array<double, 3> m_moments;
    std::array<std::array<double, 3>, 3> m_tensor{};
    std::array<double, 4> m_axes{1.0, 0.0, 0.0, 0.0};
};

} // namespace rotgen
