// rotgen — the model's Euler angles at run time: its sequence (expr/angles.hpp, the model's
// angle_convention) as the runtime's euler_sequence (runtime/euler_sequence.hpp), passed to every
// function here, and the conversions the engine needs
// between angles, the quaternion (R(q) = A^T) and body omega. The chapter's z-x-z goes through
// runtime/rotation.hpp's own functions (its results unchanged); any other sequence through the
// general ones.
#pragma once

#include "expr/angles.hpp"

#include <euler_sequence.hpp> // runtime
#include <rotation.hpp>       // runtime

#include <array>
#include <string>

namespace rotgen {

// The runtime's sequence of a model's convention.
inline euler_sequence sequence_of(const angle_convention& c) {
    return euler_sequence{c.axes};
}

// q = q_a(alpha) (x) q_b(beta) (x) q_c(gamma), w >= 0.
template <class T>
Eigen::Quaternion<T> quaternion_of_angles(const euler_sequence& s, T a0, T a1, T a2) {
    if (s.is_zxz()) return quaternion_from_euler<T>(a0, a1, a2);
    return sequence_quaternion<T>(s, {a0, a1, a2});
}

// The angles of a quaternion (any non-zero norm), in the sequence's ranges.
template <class T>
std::array<T, 3> angles_of_quaternion(const euler_sequence& s, const Eigen::Quaternion<T>& q) {
    if (s.is_zxz()) {
        const euler_angles<T> e = euler_from_quaternion(q);
        return {e.phi, e.theta, e.psi};
    }
    return sequence_angles_from_quaternion(s, q);
}

// |sin beta| (proper Euler) or |cos beta| (Tait-Bryan): 0 on the singular set.
inline double chart_distance(const euler_sequence& s, double beta) {
    return sequence_chart_distance(s, beta);
}

// "sin theta" / "cos pitch": the factor that vanishes on the singular set, in words.
inline std::string distance_words(const angle_convention& c) {
    return (c.proper() ? "sin " : "cos ") + c.names[1];
}

// "|sin theta|" / "|cos pitch|": the chart distance in words.
inline std::string distance_label(const angle_convention& c) {
    return "|" + distance_words(c) + "|";
}

// "theta = 0 or pi" / "pitch = -pi/2 or pi/2": the singular set in words.
inline std::string singular_words(const angle_convention& c) {
    return c.names[1] + (c.proper() ? " = 0 or pi" : " = -pi/2 or pi/2");
}

// J with omega = J q_dot (5.30 for z-x-z).
template <class T> mat3<T> omega_jacobian_at(const euler_sequence& s, const std::array<T, 3>& q) {
    return sequence_omega_jacobian(s, q);
}

} // namespace rotgen
