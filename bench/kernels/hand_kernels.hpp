// The hand-written kernels kernel_bench times rotgen's generated ones against (bench/kernels/
// emit_bench.cpp): the same equations written by hand, sin/cos once, the parameters folded in, as a
// careful person would. Lagrangian form, y = (phi, theta, psi, phi_dot, theta_dot, psi_dot),
// z-x-z Euler angles, omega in body axes (5.30).
#pragma once

#include <cmath>
#include <string>

namespace hand_kernels {

// The heavy symmetric top from (5.73): Euler-Lagrange equations with p_phi, p_psi conserved.
struct heavy_top_hand {
    double I1 = 1.0, I3 = 0.5, Mgh = 1.0 * 9.81 * 0.1;
    void operator()(const double* y, double* f) const {
        const double st = std::sin(y[1]), ct = std::cos(y[1]);
        const double phid = y[3], thetad = y[4], psid = y[5];
        const double w3 = phid * ct + psid;
        f[0] = phid, f[1] = thetad, f[2] = psid;
        f[4] = (I1 * phid * phid * st * ct - I3 * w3 * phid * st + Mgh * st) / I1;
        f[3] = (I3 * w3 - 2 * I1 * phid * ct) * thetad / (I1 * st);
        f[5] = -(f[3] * ct - phid * st * thetad);
    }
};

// Any tensor, gravity: omega = J q_dot, omega_dot = I^{-1}(r x (-M g e) - omega x I omega),
// q_ddot = J^{-1}(omega_dot - J_dot q_dot). I and I^{-1} precomputed.
struct euler_hand {
    double I[3][3], Iinv[3][3], Mg, r[3];
    explicit euler_hand(const double (&tensor)[3][3], double mass_g, const double (&com)[3])
        : Mg(mass_g) {
        for (int i = 0; i < 3; ++i) {
            r[i] = com[i];
            for (int j = 0; j < 3; ++j)
                I[i][j] = tensor[i][j];
        }
        const double det = I[0][0] * (I[1][1] * I[2][2] - I[1][2] * I[2][1]) -
                           I[0][1] * (I[1][0] * I[2][2] - I[1][2] * I[2][0]) +
                           I[0][2] * (I[1][0] * I[2][1] - I[1][1] * I[2][0]);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
                Iinv[i][j] = (I[r0][c0] * I[r1][c1] - I[r0][c1] * I[r1][c0]) / det;
            }
    }
    void operator()(const double* y, double* f) const {
        const double st = std::sin(y[1]), ct = std::cos(y[1]), sp = std::sin(y[2]),
                     cp = std::cos(y[2]);
        const double phid = y[3], thetad = y[4], psid = y[5];
        const double w[3] = {phid * st * sp + thetad * cp, phid * st * cp - thetad * sp,
                             phid * ct + psid};
        double l[3];
        for (int i = 0; i < 3; ++i)
            l[i] = I[i][0] * w[0] + I[i][1] * w[1] + I[i][2] * w[2];
        const double e[3] = {st * sp, st * cp, ct};
        const double b[3] = {-Mg * (r[1] * e[2] - r[2] * e[1]) - (w[1] * l[2] - w[2] * l[1]),
                             -Mg * (r[2] * e[0] - r[0] * e[2]) - (w[2] * l[0] - w[0] * l[2]),
                             -Mg * (r[0] * e[1] - r[1] * e[0]) - (w[0] * l[1] - w[1] * l[0])};
        const double jdot[3] = {phid * (ct * thetad * sp + st * cp * psid) - thetad * sp * psid,
                                phid * (ct * thetad * cp - st * sp * psid) - thetad * cp * psid,
                                -phid * st * thetad};
        double a[3];
        for (int i = 0; i < 3; ++i)
            a[i] = Iinv[i][0] * b[0] + Iinv[i][1] * b[1] + Iinv[i][2] * b[2] - jdot[i];
        f[0] = phid, f[1] = thetad, f[2] = psid;
        f[3] = (a[0] * sp + a[1] * cp) / st;
        f[4] = a[0] * cp - a[1] * sp;
        f[5] = a[2] - f[3] * ct;
    }
};

// The free asymmetric top: Euler's equations (5.87-5.89) in principal axes, then
// q_ddot = J^{-1}(omega_dot - J_dot q_dot) as above. The ratios (I2 - I3)/I1 ... precomputed.
struct free_top_hand {
    double k1, k2, k3;
    free_top_hand(double I1, double I2, double I3)
        : k1((I2 - I3) / I1), k2((I3 - I1) / I2), k3((I1 - I2) / I3) {}
    void operator()(const double* y, double* f) const {
        const double st = std::sin(y[1]), ct = std::cos(y[1]), sp = std::sin(y[2]),
                     cp = std::cos(y[2]);
        const double phid = y[3], thetad = y[4], psid = y[5];
        const double pst = phid * st;
        const double w1 = pst * sp + thetad * cp, w2 = pst * cp - thetad * sp,
                     w3 = phid * ct + psid;
        const double tp = thetad * psid, ptc = phid * thetad * ct;
        const double a1 = k1 * w2 * w3 - (ptc * sp + pst * cp * psid - tp * sp);
        const double a2 = k2 * w3 * w1 - (ptc * cp - pst * sp * psid - tp * cp);
        f[0] = phid, f[1] = thetad, f[2] = psid;
        f[3] = (a1 * sp + a2 * cp) / st;
        f[4] = a1 * cp - a2 * sp;
        f[5] = k3 * w1 * w2 + pst * thetad - f[3] * ct;
    }
};

// The damped, driven heavy top: (5.73) with Q = -c q_dot + J^T (0, 0, A sin(w t)); the momenta's
// equations d/dt p_phi = Q_phi, d/dt p_psi = I3 d/dt omega3 = Q_psi solved for phi_ddot, psi_ddot.
struct damped_top_hand {
    double I1 = 1.0, I3 = 0.5, Mgh = 1.0 * 9.81 * 0.1, c = 0.05, A = 0.2, w = 3.0, t = 0.5;
    void operator()(const double* y, double* f) const {
        const double st = std::sin(y[1]), ct = std::cos(y[1]);
        const double phid = y[3], thetad = y[4], psid = y[5];
        const double w3 = phid * ct + psid;
        const double tau3 = A * std::sin(w * t);
        f[0] = phid, f[1] = thetad, f[2] = psid;
        f[4] = ((I1 * phid * ct - I3 * w3) * phid * st + Mgh * st - c * thetad) / I1;
        f[3] = ((I3 * w3 - 2 * I1 * phid * ct) * thetad * st - c * (phid - ct * psid)) /
               (I1 * st * st);
        f[5] = (tau3 - c * psid) / I3 - f[3] * ct + phid * st * thetad;
    }
};

// Calls v(description, kernel) for each hand-written kernel of the model (defaults of the model
// file; the damped top at t = 0.5, as the benchmark calls the generated kernels).
template <class Visit> void for_each_hand(const std::string& model, Visit v) {
    if (model == "heavy_top") {
        v("(5.73) Euler-Lagrange", heavy_top_hand{});
        const double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 0.5}};
        const double com[3] = {0, 0, 0.1};
        v("Euler's equations + J^{-1}", euler_hand(I, 9.81, com));
    } else if (model == "free_asymmetric_top") {
        v("Euler's equations (5.87-5.89) + J^{-1}", free_top_hand(1.0, 2.0, 3.0));
    } else if (model == "full_tensor_top") {
        const double I[3][3] = {{2.0, -0.3, 0.2}, {-0.3, 2.5, -0.1}, {0.2, -0.1, 1.5}};
        const double com[3] = {0.05, -0.02, 0.15};
        v("Euler's equations + J^{-1}", euler_hand(I, 1.2 * 9.81, com));
    } else if (model == "damped_driven_top") {
        v("(5.73) with damping and drive", damped_top_hand{});
    }
}

} // namespace hand_kernels
