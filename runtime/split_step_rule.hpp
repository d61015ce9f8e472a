// rotgen runtime — a fixed step for the splitting methods from a tolerance (split2/4/6 have no
// error estimate; steppers/splitting.hpp).
//
//   h = c_p · rtol^(1/p) / ω_V,   capped at the time span,
//
// ω_V = sqrt(κ / I_min) the frequency of the potential's slow motion (a pendulum's), κ the torque's
// stiffness at the start, max_i |τ(q0 ⊗ δ_i) − τ(q0 ⊗ δ_i⁻¹)| / (2δ) over small rotations δ_i
// about the body axes (central differences, δ = 1e-4), I_min the smallest principal moment. The
// spin does not enter: the free flow is exact whatever it is. c_p = 1, 1.8, 1.3 for p = 2, 4, 6
// were measured on the heavy top (I = (1, 1, 0.5) and (1, 1.2, 0.5), M g h = 0.981, spin 10), where
// they make the error over one slow period 2π/ω_V about rtol/2 (tests/runtime/test_splitting.cpp).
// Without a torque (κ = 0) the free flow is exact and one step spans the run. A torque that varies
// in time faster than ω_V needs a step chosen by hand.
#pragma once

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>

#include "split_system.hpp"

namespace rotgen {

template <class S, class T, class Y>
T split_step_for_tolerance(const S& sys, int order, T rtol, T t0, const Y& y0, T span) {
    using std::abs;
    using std::pow;
    using std::sqrt;
    const T delta = T(1e-4);
    const Eigen::Quaternion<T> q0(y0[0], y0[1], y0[2], y0[3]);
    T kappa = 0;
    for (int i = 0; i < 3; ++i) {
        T tau_plus[3], tau_minus[3];
        for (int sign = -1; sign <= 1; sign += 2) {
            Eigen::Matrix<T, 3, 1> axis = Eigen::Matrix<T, 3, 1>::Zero();
            axis[i] = T(1);
            const Eigen::Quaternion<T> q =
                q0 * Eigen::Quaternion<T>(Eigen::AngleAxis<T>(T(sign) * delta, axis));
            const T y[7] = {q.w(), q.x(), q.y(), q.z(), T(0), T(0), T(0)};
            sys.torque(t0, y, sign > 0 ? tau_plus : tau_minus);
        }
        for (int j = 0; j < 3; ++j)
            kappa = std::max(kappa, abs(tau_plus[j] - tau_minus[j]) / (T(2) * delta));
    }
    span = abs(span);
    if (!(kappa > T(0))) return span;
    const auto& in = sys.principal_moments();
    const T i_min = std::min({T(in[0]), T(in[1]), T(in[2])});
    const T c = order == 2 ? T(2) : order == 4 ? T(2.5) : T(1.6);
    const T h = c * pow(rtol, T(1) / T(order)) / sqrt(kappa / i_min);
    return std::min(h, span);
}

} // namespace rotgen
