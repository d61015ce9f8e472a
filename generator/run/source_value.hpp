// rotgen — a recorded column at a sample from its value_source (run/kernels.hpp), on any scalar:
// double for the rows, run/dual.hpp's dual for their derivatives along the sensitivity keys (the
// same code differentiated, so a derivative follows the branch its value takes).
//
// Angles are the model's sequence s (z-x-z: phi, theta, psi, 5.25), omega in body axes (5.30), the
// quaternion scalar first, body -> space (R(q) = A^T), taken with q0 >= 0.
#pragma once

#include "run/angle_chart.hpp"
#include "run/dual.hpp"
#include "run/kernels.hpp"

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <optional>

namespace rotgen {

namespace detail {

// J^-1 w for the Euler rates: LU for doubles (the rows as before), the cofactor inverse for duals.
inline Eigen::Vector3d solve3(const Eigen::Matrix3d& J, const Eigen::Vector3d& w) {
    return J.lu().solve(w);
}
inline Eigen::Matrix<dual, 3, 1> solve3(const mat3<dual>& J, const Eigen::Matrix<dual, 3, 1>& w) {
    return J.inverse() * w;
}

// l = I omega, or a gyrostat's (or a run with sensitivities') total from the record program.
template <class T>
Eigen::Matrix<T, 3, 1> momentum_of(const value_source& src, const T* out, const mat3<T>& inertia,
                                   const Eigen::Matrix<T, 3, 1>& w) {
    if (src.momentum < 0) return inertia * w;
    const auto m = static_cast<std::size_t>(src.momentum);
    return Eigen::Matrix<T, 3, 1>(out[m], out[m + 1], out[m + 2]);
}

} // namespace detail

// source_value (run/kernels.hpp) on the scalar T: y the form's state, out the record program's
// outputs; `e` caches the angles between calls at one sample.
template <class T>
T source_value_of(const euler_sequence& s, const value_source& src, const T* y, const T* out,
                  const mat3<T>& inertia, std::optional<std::array<T, 3>>& e) {
    using std::cos;
    using std::sin;
    using vec3 = Eigen::Matrix<T, 3, 1>;
    if (src.kind == value_source::compiled) return out[static_cast<std::size_t>(src.index)];
    if (src.kind == value_source::quaternion_of_state ||
        src.kind == value_source::quaternion_of_angles) {
        Eigen::Quaternion<T> q = src.kind == value_source::quaternion_of_state
                                     ? Eigen::Quaternion<T>(y[0], y[1], y[2], y[3]).normalized()
                                     : quaternion_of_angles<T>(s, y[0], y[1], y[2]);
        if (q.w() < T(0)) q.coeffs() = -q.coeffs(); // q and -q: the same attitude
        const T c[4] = {q.w(), q.x(), q.y(), q.z()};
        return c[src.index];
    }
    if (!e) e = angles_of_quaternion<T>(s, Eigen::Quaternion<T>(y[0], y[1], y[2], y[3]));
    const vec3 w(y[4], y[5], y[6]);
    if (src.kind == value_source::angle) return (*e)[static_cast<std::size_t>(src.index)];
    if (!s.is_zxz()) {
        const mat3<T> J = omega_jacobian_at<T>(s, *e); // undefined on the singular set
        const vec3 v = src.kind == value_source::euler_rate
                           ? vec3(detail::solve3(J, w))
                           : vec3(J.transpose() * detail::momentum_of<T>(src, out, inertia, w));
        return v[src.index];
    }
    const T st = sin((*e)[1]), ct = cos((*e)[1]), sp = sin((*e)[2]), cp = cos((*e)[2]);
    if (src.kind == value_source::euler_rate) {
        const T phi_dot = (w[0] * sp + w[1] * cp) / st; // undefined at theta = 0, pi
        return src.index == 0   ? phi_dot
               : src.index == 1 ? T(w[0] * cp - w[1] * sp)
                                : T(w[2] - phi_dot * ct);
    }
    const vec3 l = detail::momentum_of<T>(src, out, inertia, w); // p = J^T l, J of (5.30)
    return src.index == 0   ? T(st * sp * l[0] + st * cp * l[1] + ct * l[2])
           : src.index == 1 ? T(cp * l[0] - sp * l[1])
                            : T(l[2]);
}

} // namespace rotgen
