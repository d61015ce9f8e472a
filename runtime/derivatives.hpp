/// \file
/// rotgen runtime — evaluating f, ∂f/∂y and ∂f/∂t of a system, with work counters.
///
/// The Jacobian comes from `system.jacobian` when the system has one; otherwise it is formed by
/// forward differences, column by column (Hairer–Wanner II, IV.8, and their RADAU5/RODAS codes):
///   J(:, j) ≈ (f(t, y + δ_j e_j) − f(t, y)) / δ_j,   δ_j = sqrt(eps · max(1e-5, |y_j|)),
/// which costs n extra evaluations of f and has error O(sqrt(eps)) relative — enough for the
/// iteration matrices of Newton and Rosenbrock methods (for Rosenbrock methods an inexact
/// Jacobian lowers the order; give an analytic Jacobian for the stated order).
/// ∂f/∂t (needed by Rosenbrock methods on non-autonomous problems) is a central difference.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "result.hpp"
#include "system.hpp"

namespace rotgen::detail {

/// dydt = f(t, y)
template <class S, class T, class V>
void eval_rhs(const S& sys, T t, const V& y, V& dydt, step_stats& stats) {
    sys.rhs(t, y.data(), dydt.data());
    ++stats.rhs_evals;
}

/// J = ∂f/∂y at (t, y). `f0` must hold f(t, y) (used only by the finite-difference fallback).
template <class S, class T, class V, class M>
void eval_jacobian(const S& sys, T t, const V& y, const V& f0, M& jac, step_stats& stats) {
    ++stats.jac_evals;
    if constexpr (has_jacobian_v<S, T>) {
        (void)f0;
        sys.jacobian(t, y.data(), jac.data());
    } else {
        using std::abs;
        using std::max;
        using std::sqrt;
        const T eps = std::numeric_limits<T>::epsilon();
        V yp = y;
        V fp = f0;
        for (Eigen::Index j = 0; j < y.size(); ++j) {
            const T delta = sqrt(eps * max(T(1e-5), abs(y[j])));
            yp[j] = y[j] + delta;
            const T step = yp[j] - y[j]; // the increment actually represented
            eval_rhs(sys, t, yp, fp, stats);
            jac.col(j) = (fp - f0) / step;
            yp[j] = y[j];
        }
    }
}

/// ft = ∂f/∂t at (t, y) by a central difference in t (two evaluations of f):
///   ft ≈ (f(t + δ, y) − f(t − δ, y)) / (2δ),  δ = eps^(1/3)·max(1, |t|),
/// error ~ δ²|f_ttt|/6 + eps·|f|/δ = O(eps^(2/3)) (a forward difference would give only
/// O(sqrt(eps)), which caps the accuracy of Rosenbrock methods on time-dependent problems).
template <class S, class T, class V>
void eval_time_derivative(const S& sys, T t, const V& y, V& ft, V& work, step_stats& stats) {
    using std::abs;
    using std::cbrt;
    using std::max;
    const T delta = cbrt(std::numeric_limits<T>::epsilon()) * max(T(1), abs(t));
    const T tp = t + delta, tm = t - delta;
    eval_rhs(sys, tp, y, ft, stats);
    eval_rhs(sys, tm, y, work, stats);
    ft = (ft - work) / (tp - tm);
}

} // namespace rotgen::detail
