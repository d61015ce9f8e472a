// rotgen bench — the common representation every formulation's final state is mapped to, so
// that errors of different forms (Lagrangian, Hamiltonian, reduced, body) are comparable.
//
//   quantities  omega1..3 (body angular velocity, 5.30), phi, theta, psi (z-x-z Euler angles,
//               5.3), phi_dot, theta_dot, psi_dot, and the attitude A (passive, body <- space,
//               5.25) — each present only if the form determines it:
//     lagrangian   everything (angles and rates are the state; omega and A from the kernels)
//     hamiltonian  everything (rates from the rhs: q_dot = dH/dp)
//     reduced      the kept angles, all three rates (ignored ones from `ignored_rates`), omega
//                  if it does not depend on an ignored angle; no A
//     body, quaternion   A from the quaternion, angles from A, omega, rates = J^{-1} omega
//     body, omega only   omega
//   error        max over the quantities that EVERY configuration of the sweep determines (the
//                `compared` set, listed in results.md) of |x - x_ref|; phi and psi are compared
//                modulo 2 pi.
//   orientation  the angle of A_ref A^T (rotation.hpp: orientation_error), if A is known.
//   sampled error  the bench's error (issue 50: the measure of generator/bench/sampled_error.hpp
//                `rotgen bench`'s choice and `method: auto` use), max over the scene's samples of
//                the attitude angle (where every configuration determines A) and of
//                |omega - omega_ref| / max |omega_ref| (where every one determines omega); with
//                neither, of each compared quantity's |x - x_ref| / max(1, max |x_ref|).
// Everything is evaluated in long double from the final state, whatever the scalar of the run.
#pragma once

#include "rotation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace rotgen::bench {

enum quantity : int {
    q_omega1,
    q_omega2,
    q_omega3,
    q_phi,
    q_theta,
    q_psi,
    q_phi_dot,
    q_theta_dot,
    q_psi_dot,
    n_quantities
};

inline const char* quantity_name(int q) {
    static const char* const names[n_quantities] = {
        "omega1", "omega2", "omega3", "phi", "theta", "psi", "phi_dot", "theta_dot", "psi_dot"};
    return names[q];
}

struct common_state {
    std::array<long double, n_quantities> v{};
    std::array<bool, n_quantities> has{};
    mat3<long double> A = mat3<long double>::Identity();
    bool has_A = false;

    void set(int q, long double x) {
        v[static_cast<std::size_t>(q)] = x;
        has[static_cast<std::size_t>(q)] = true;
    }
    // A from a row-major 3x3 array.
    void set_rotation(const long double* a) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                A(i, j) = a[3 * i + j];
        has_A = true;
    }
    void set_rotation(const mat3<long double>& a) {
        A = a;
        has_A = true;
    }
    // phi, theta, psi from A (body form)
    void angles_from_rotation() {
        const euler_angles<long double> e = euler_from_matrix(A);
        set(q_phi, e.phi);
        set(q_theta, e.theta);
        set(q_psi, e.psi);
    }
    // q_dot = J^{-1} omega from (5.30): phi_dot = (omega1 sin psi + omega2 cos psi) / sin theta,
    // theta_dot = omega1 cos psi - omega2 sin psi, psi_dot = omega3 - phi_dot cos theta.
    void rates_from_omega() {
        using std::cos;
        using std::sin;
        const long double th = v[q_theta], ps = v[q_psi];
        const long double w1 = v[q_omega1], w2 = v[q_omega2], w3 = v[q_omega3];
        const long double phi_dot = (w1 * sin(ps) + w2 * cos(ps)) / sin(th);
        set(q_phi_dot, phi_dot);
        set(q_theta_dot, w1 * cos(ps) - w2 * sin(ps));
        set(q_psi_dot, w3 - phi_dot * cos(th));
    }
};

// x - y for angles, in (-pi, pi]
inline long double angle_difference(long double x, long double y) {
    using std::remainder;
    return remainder(x - y, 2.0L * 3.141592653589793238462643383279502884L);
}

// Max-norm error over the `compared` quantities (NaN if a compared quantity is missing).
inline long double state_error(const common_state& c, const common_state& ref,
                               const std::array<bool, n_quantities>& compared) {
    using std::abs;
    long double e = 0;
    for (int q = 0; q < n_quantities; ++q) {
        if (!compared[static_cast<std::size_t>(q)]) continue;
        if (!c.has[static_cast<std::size_t>(q)])
            return std::numeric_limits<long double>::quiet_NaN();
        const long double d =
            q == q_phi || q == q_psi
                ? angle_difference(c.v[static_cast<std::size_t>(q)],
                                   ref.v[static_cast<std::size_t>(q)])
                : c.v[static_cast<std::size_t>(q)] - ref.v[static_cast<std::size_t>(q)];
        if (std::isnan(d)) return std::numeric_limits<long double>::quiet_NaN();
        e = std::max(e, abs(d));
    }
    return e;
}

inline long double attitude_error(const common_state& c, const common_state& ref) {
    if (!c.has_A || !ref.has_A) return std::numeric_limits<long double>::quiet_NaN();
    return orientation_error(ref.A, c.A);
}

// What every configuration of the sweep determines: the quantities, and the attitude A.
struct comparison {
    std::array<bool, n_quantities> q{};
    bool attitude = false;
    bool has(int k) const { return q[static_cast<std::size_t>(k)]; }
};

// The sampled error (the top of this file) and the largest attitude angle over the samples of
// `run` against `ref` (same sample times; NaN where either lacks the attitude); NaN error when
// the run has another number of samples.
struct sampled_measure {
    long double error = 0, orientation = 0;
};

namespace measure_detail {

inline long double omega_norm(const common_state& c) {
    using std::sqrt;
    return sqrt(c.v[q_omega1] * c.v[q_omega1] + c.v[q_omega2] * c.v[q_omega2] +
                c.v[q_omega3] * c.v[q_omega3]);
}

// Each compared quantity's largest |x_ref| over the samples, at least 1 (the scale of its error
// where neither the attitude nor omega is compared).
inline std::array<long double, n_quantities>
reference_scales(const std::vector<common_state>& ref) {
    std::array<long double, n_quantities> s;
    s.fill(1);
    for (const auto& r : ref)
        for (std::size_t k = 0; k < s.size(); ++k)
            s[k] = std::max(s[k], std::abs(r.v[k]));
    return s;
}

} // namespace measure_detail

inline sampled_measure sampled_error(const std::vector<common_state>& run,
                                     const std::vector<common_state>& ref, const comparison& cmp) {
    const long double nan = std::numeric_limits<long double>::quiet_NaN();
    if (run.size() != ref.size() || ref.empty()) return {nan, nan};
    const bool omega = cmp.has(q_omega1) && cmp.has(q_omega2) && cmp.has(q_omega3);
    long double w_scale = 0;
    for (const auto& r : ref)
        w_scale = std::max(w_scale, measure_detail::omega_norm(r));
    if (!(w_scale > 0)) w_scale = 1;
    const auto scales = measure_detail::reference_scales(ref);
    sampled_measure m;
    m.orientation = run.front().has_A && ref.front().has_A ? 0 : nan;
    for (std::size_t i = 0; i < ref.size(); ++i) {
        const common_state &c = run[i], &r = ref[i];
        long double e = 0;
        const long double a = attitude_error(c, r); // NaN without the attitude
        if (!std::isnan(m.orientation)) m.orientation = std::max(m.orientation, a);
        if (cmp.attitude) {
            if (std::isnan(a)) return {nan, nan};
            e = std::max(e, a);
        }
        if (omega) {
            common_state d = c; // omega - omega_ref
            for (int k : {q_omega1, q_omega2, q_omega3})
                d.v[static_cast<std::size_t>(k)] -= r.v[static_cast<std::size_t>(k)];
            const long double dw = measure_detail::omega_norm(d) / w_scale;
            if (std::isnan(dw)) return {nan, nan};
            e = std::max(e, dw);
        }
        if (!omega && !cmp.attitude) { // each compared quantity relative to its scale
            std::array<bool, n_quantities> one{};
            for (int k = 0; k < n_quantities; ++k) {
                if (!cmp.has(k)) continue;
                one.fill(false);
                one[static_cast<std::size_t>(k)] = true;
                const long double d = state_error(c, r, one);
                if (std::isnan(d)) return {nan, nan};
                e = std::max(e, d / scales[static_cast<std::size_t>(k)]);
            }
        }
        m.error = std::max(m.error, e);
    }
    return m;
}

} // namespace rotgen::bench
