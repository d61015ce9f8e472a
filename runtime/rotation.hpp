/// \file
/// rotgen runtime — rotation matrices, Euler angles and unit quaternions.
///
/// Convention (the chapter's, §5.2–5.3): PASSIVE rotation matrices that map space-frame
/// coordinates to body-frame coordinates, r_body = A r_space. Euler angles z-x-z: φ about z,
/// then θ about the new x, then ψ about the new z:
///   A = Az(ψ) Ax(θ) Az(φ)                                                           (5.25)
///   Az(a) = [[cos a, sin a, 0], [−sin a, cos a, 0], [0, 0, 1]]                       (5.8)
///   Ax(a) = [[1, 0, 0], [0, cos a, sin a], [0, −sin a, cos a]]                       (5.9)
/// Angles are returned with φ, ψ ∈ [0, 2π) and θ ∈ [0, π]. At the coordinate singularity only
/// φ + ψ (θ = 0) or φ − ψ (θ = π) is defined; there ψ = 0 and the whole rotation goes into φ
/// (θ = 0: A = Az(φ); θ = π: A = Ax(π) Az(φ), so in both cases φ = atan2(A12, A11)). The
/// singular branch is taken when sin θ <= 4·eps.
///
/// Quaternions: a unit quaternion q = (w, x, y, z) = (cos(α/2), n sin(α/2)) describes the ACTIVE
/// rotation R(q) by the angle α about the unit axis n that carries body-frame coordinates to
/// space-frame coordinates, r_space = R(q) r_body; the passive matrix of this file is
///   A = R(q)ᵀ.
/// With this choice q from the Euler angles is q_z(φ) ⊗ q_x(θ) ⊗ q_z(ψ) (q_n(a) = (cos a/2, n sin
/// a/2)) and the kinematics with the body angular velocity ω is q̇ = ½ q ⊗ (0, ω) — the body form's
/// layout y = (qw, qx, qy, qz, ω1, ω2, ω3). q and −q are the same rotation; functions here
/// return w >= 0. (Eigen::Quaternion stores (x, y, z, w) in coeffs(); use w(), x(), y(), z().)
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace rotgen {

/// A 3×3 matrix of scalar T (rotation matrices, inertia tensors).
template <class T> using mat3 = Eigen::Matrix<T, 3, 3>;

/// Az(a), (5.8): passive rotation of the coordinate axes by a about z.
template <class T> mat3<T> rot_z(T a) {
    using std::cos;
    using std::sin;
    const T c = cos(a), s = sin(a);
    mat3<T> m;
    m << c, s, T(0), -s, c, T(0), T(0), T(0), T(1);
    return m;
}

/// Ax(a), (5.9)
template <class T> mat3<T> rot_x(T a) {
    using std::cos;
    using std::sin;
    const T c = cos(a), s = sin(a);
    mat3<T> m;
    m << T(1), T(0), T(0), T(0), c, s, T(0), -s, c;
    return m;
}

/// Ay(a), (5.9)
template <class T> mat3<T> rot_y(T a) {
    using std::cos;
    using std::sin;
    const T c = cos(a), s = sin(a);
    mat3<T> m;
    m << c, T(0), -s, T(0), T(1), T(0), s, T(0), c;
    return m;
}

/// A = Az(ψ) Ax(θ) Az(φ), written out as in (5.25); z-x-z, passive, body ← space.
template <class T> mat3<T> euler_matrix(T phi, T theta, T psi) {
    using std::cos;
    using std::sin;
    const T cf = cos(phi), sf = sin(phi), ct = cos(theta), st = sin(theta), cp = cos(psi),
            sp = sin(psi);
    mat3<T> a;
    a << cp * cf - sp * ct * sf, cp * sf + sp * ct * cf, sp * st,  //
        -sp * cf - cp * ct * sf, -sp * sf + cp * ct * cf, cp * st, //
        st * sf, -st * cf, ct;
    return a;
}

/// Rotation `first` followed by rotation `second`: B = second · first (5.10).
template <class T> mat3<T> compose(const mat3<T>& second, const mat3<T>& first) {
    return second * first;
}

/// Inverse of a rotation matrix: its transpose.
template <class T> mat3<T> inverse(const mat3<T>& a) {
    return a.transpose();
}

/// ‖AᵀA − I‖_max <= tol
template <class T> bool is_orthogonal(const mat3<T>& a, T tol) {
    return (a.transpose() * a - mat3<T>::Identity()).cwiseAbs().maxCoeff() <= tol;
}

/// Orthogonal with det A = +1 (a rotation).
template <class T> bool is_proper_rotation(const mat3<T>& a, T tol) {
    using std::abs;
    return is_orthogonal(a, tol) && abs(a.determinant() - T(1)) <= tol;
}

/// Orthogonal with det A = −1 (a rotation combined with a reflection).
template <class T> bool is_improper_rotation(const mat3<T>& a, T tol) {
    using std::abs;
    return is_orthogonal(a, tol) && abs(a.determinant() + T(1)) <= tol;
}

/// z-x-z Euler angles (φ, θ, ψ) in radians, the chapter's convention (5.3): A = Az(ψ) Ax(θ)
/// Az(φ), passive, body ← space (5.25).
template <class T> struct euler_angles {
    T phi;   ///< [0, 2π), about the space z axis
    T theta; ///< [0, π],  about the line of nodes (intermediate x axis)
    T psi;   ///< [0, 2π), about the body z axis
};

namespace detail {
template <class T> T wrap_two_pi(T a) {
    using std::fmod;
    const T two_pi = T(2) * T(EIGEN_PI);
    a = fmod(a, two_pi);
    if (a < T(0)) a += two_pi;
    if (a >= two_pi) a = T(0);
    return a;
}
} // namespace detail

/// Euler angles (z-x-z, passive, φ, ψ ∈ [0, 2π), θ ∈ [0, π]) of a proper rotation matrix.
/// From (5.25) (1-based indices A_ij):
///   θ = atan2(sqrt(A31² + A32²), A33)            (A31 = sinθ sinφ, A32 = −sinθ cosφ)
///   φ = atan2(A31, −A32)
///   A11 + A22 = (1 + cosθ) cos(φ+ψ),  A12 − A21 = (1 + cosθ) sin(φ+ψ)   → ψ = (φ+ψ) − φ, θ <= π/2
///   A11 − A22 = (1 − cosθ) cos(ψ−φ),  A12 + A21 = (1 − cosθ) sin(φ−ψ)   → ψ = φ − (φ−ψ), θ > π/2
/// Taking ψ from the well-conditioned sum (or difference) keeps A reproduced to rounding even
/// close to the singularity; at it (sin θ <= 4·eps) ψ = 0, φ = atan2(A12, A11), θ = 0 or π.
template <class T> euler_angles<T> euler_from_matrix(const mat3<T>& a) {
    using std::atan2;
    using std::hypot;
    const T eps = std::numeric_limits<T>::epsilon();
    const T st = hypot(a(2, 0), a(2, 1));
    euler_angles<T> e;
    if (st <= T(4) * eps) {
        e.theta = a(2, 2) > T(0) ? T(0) : T(EIGEN_PI);
        e.psi = T(0);
        e.phi = detail::wrap_two_pi(atan2(a(0, 1), a(0, 0)));
        return e;
    }
    e.theta = atan2(st, a(2, 2));
    const T phi = atan2(a(2, 0), -a(2, 1));
    T psi;
    if (a(2, 2) >= T(0))
        psi = atan2(a(0, 1) - a(1, 0), a(0, 0) + a(1, 1)) - phi; // (φ+ψ) − φ
    else
        psi = phi - atan2(a(0, 1) + a(1, 0), a(0, 0) - a(1, 1)); // φ − (φ−ψ)
    e.phi = detail::wrap_two_pi(phi);
    e.psi = detail::wrap_two_pi(psi);
    return e;
}

/// A = Az(ψ) Ax(θ) Az(φ) of the angles e, (5.25).
template <class T> mat3<T> euler_matrix(const euler_angles<T>& e) {
    return euler_matrix(e.phi, e.theta, e.psi);
}

/// Passive matrix A = R(q)ᵀ of a quaternion (normalised first). R(q), the active rotation:
///   [[1−2(y²+z²), 2(xy−wz), 2(xz+wy)], [2(xy+wz), 1−2(x²+z²), 2(yz−wx)], [2(xz−wy), 2(yz+wx),
///   1−2(x²+y²)]]
template <class T> mat3<T> matrix_from_quaternion(const Eigen::Quaternion<T>& qin) {
    const Eigen::Quaternion<T> q = qin.normalized();
    const T w = q.w(), x = q.x(), y = q.y(), z = q.z();
    mat3<T> r;
    r << T(1) - T(2) * (y * y + z * z), T(2) * (x * y - w * z), T(2) * (x * z + w * y), //
        T(2) * (x * y + w * z), T(1) - T(2) * (x * x + z * z), T(2) * (y * z - w * x),  //
        T(2) * (x * z - w * y), T(2) * (y * z + w * x), T(1) - T(2) * (x * x + y * y);
    return r.transpose();
}

/// Unit quaternion (w >= 0) of a proper rotation matrix A (passive), from R = Aᵀ by Shepperd's
/// method: the largest of 4w², 4x², 4y², 4z² (from the trace and the diagonal) is taken first.
template <class T> Eigen::Quaternion<T> quaternion_from_matrix(const mat3<T>& a) {
    using std::sqrt;
    const mat3<T> r = a.transpose();
    const T tr = r.trace();
    T w, x, y, z;
    if (tr >= r(0, 0) && tr >= r(1, 1) && tr >= r(2, 2)) {
        const T s = T(2) * sqrt(T(1) + tr); // s = 4w
        w = s / T(4);
        x = (r(2, 1) - r(1, 2)) / s;
        y = (r(0, 2) - r(2, 0)) / s;
        z = (r(1, 0) - r(0, 1)) / s;
    } else if (r(0, 0) >= r(1, 1) && r(0, 0) >= r(2, 2)) {
        const T s = T(2) * sqrt(T(1) + r(0, 0) - r(1, 1) - r(2, 2)); // s = 4x
        w = (r(2, 1) - r(1, 2)) / s;
        x = s / T(4);
        y = (r(0, 1) + r(1, 0)) / s;
        z = (r(0, 2) + r(2, 0)) / s;
    } else if (r(1, 1) >= r(2, 2)) {
        const T s = T(2) * sqrt(T(1) + r(1, 1) - r(0, 0) - r(2, 2)); // s = 4y
        w = (r(0, 2) - r(2, 0)) / s;
        x = (r(0, 1) + r(1, 0)) / s;
        y = s / T(4);
        z = (r(1, 2) + r(2, 1)) / s;
    } else {
        const T s = T(2) * sqrt(T(1) + r(2, 2) - r(0, 0) - r(1, 1)); // s = 4z
        w = (r(1, 0) - r(0, 1)) / s;
        x = (r(0, 2) + r(2, 0)) / s;
        y = (r(1, 2) + r(2, 1)) / s;
        z = s / T(4);
    }
    Eigen::Quaternion<T> q(w, x, y, z);
    if (q.w() < T(0)) q.coeffs() = -q.coeffs();
    q.normalize();
    return q;
}

/// q = q_z(φ) ⊗ q_x(θ) ⊗ q_z(ψ), the quaternion whose passive matrix is Az(ψ) Ax(θ) Az(φ).
template <class T> Eigen::Quaternion<T> quaternion_from_euler(T phi, T theta, T psi) {
    using std::cos;
    using std::sin;
    const Eigen::Quaternion<T> qf(cos(phi / T(2)), T(0), T(0), sin(phi / T(2)));
    const Eigen::Quaternion<T> qt(cos(theta / T(2)), sin(theta / T(2)), T(0), T(0));
    const Eigen::Quaternion<T> qp(cos(psi / T(2)), T(0), T(0), sin(psi / T(2)));
    Eigen::Quaternion<T> q = qf * qt * qp;
    if (q.w() < T(0)) q.coeffs() = -q.coeffs();
    return q;
}

/// The z-x-z angles of the attitude quaternion q (scalar first, active, R(q) = Aᵀ; normalised
/// first), with the ranges and the singular cases of euler_from_matrix.
template <class T> euler_angles<T> euler_from_quaternion(const Eigen::Quaternion<T>& q) {
    return euler_from_matrix(matrix_from_quaternion(q));
}

/// Rotation angle α ∈ [0, π] of a rotation matrix M:
///   cos α = (tr M − 1)/2,  sin α = ½‖(M32 − M23, M13 − M31, M21 − M12)‖,  α = atan2(sin α, cos α)
/// (accurate for small angles and near π, unlike acos of the trace).
template <class T> T rotation_angle(const mat3<T>& m) {
    using std::atan2;
    const Eigen::Matrix<T, 3, 1> v(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
    return atan2(v.norm() / T(2), (m.trace() - T(1)) / T(2));
}

/// Orientation error between two attitudes: the angle of A_ref Aᵀ, in [0, π].
template <class T> T orientation_error(const mat3<T>& a_ref, const mat3<T>& a) {
    return rotation_angle<T>(a_ref * a.transpose());
}

} // namespace rotgen
