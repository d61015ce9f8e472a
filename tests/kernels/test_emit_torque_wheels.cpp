// Torque-driven wheels' generated kernels (tests/kernels/models/torque_wheels.yaml: a full tensor,
// three wheels on skewed axes whose motor torques use t, omega, the angles and a rate) against
// Newton-Euler written here from issue 52's convention, at random states:
//   I omega_dot + omega x (I omega + h) = -sum_k tau_k a_k,   p_k' = tau_k,   h = sum_k p_k a_k,
// I without the wheels' axial moments, p_k = J (a_k . omega + alpha_dot_k) a state of the run.
// The body form's rates exactly; the Lagrangian form's omega_dot along its flow (central
// differences) and its p'; the Hamiltonian form at the matching state (p_q = J^T (I omega + h)):
// q_dot, p_k' and p_q' (= d/dt p_q along the Lagrangian flow); each analytic Jacobian against
// central differences of its rhs.
#include "torque_wheels_body.hpp"
#include "torque_wheels_hamiltonian.hpp"
#include "torque_wheels_lagrangian.hpp"

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace {

namespace lag = rotgen::models::torque_wheels_lagrangian;
namespace ham = rotgen::models::torque_wheels_hamiltonian;
namespace bod = rotgen::models::torque_wheels_body;

struct truth {
    Eigen::Matrix3d I;
    std::array<Eigen::Vector3d, 3> a;
    double k = 0.3;
    truth() {
        I << 2, 0.2, 0, 0.2, 3, -0.2, 0, -0.2, 4.5;
        a = {Eigen::Vector3d(1, 0.2, 0).normalized(), Eigen::Vector3d(0, 1, 0.3).normalized(),
             Eigen::Vector3d(0.1, -0.2, 1).normalized()};
    }
    // the motor torques of the model file, written again
    std::array<double, 3> tau(double t, const double* q, double phi_dot,
                              const Eigen::Vector3d& w) const {
        return {k * std::sin(t) - 0.2 * w[0], 0.4 * std::cos(q[1]) + 0.1 * phi_dot,
                0.3 * w[1] * w[2] - 0.2 * std::sin(q[2])};
    }
    Eigen::Vector3d h(const double* p) const { return p[0] * a[0] + p[1] * a[1] + p[2] * a[2]; }
    Eigen::Vector3d omega_dot(const Eigen::Vector3d& w, const double* p,
                              const std::array<double, 3>& tau) const {
        Eigen::Vector3d rhs = -w.cross(I * w + h(p));
        for (int i = 0; i < 3; ++i)
            rhs -= tau[i] * a[i];
        return I.lu().solve(rhs);
    }
};

// z-x-z: omega = J q_dot (5.30)
Eigen::Vector3d omega_of(const double* q, const double* qd) {
    const double st = std::sin(q[1]), ct = std::cos(q[1]), sp = std::sin(q[2]), cp = std::cos(q[2]);
    return {qd[0] * st * sp + qd[1] * cp, qd[0] * st * cp - qd[1] * sp, qd[0] * ct + qd[2]};
}

// The largest |J - central differences of rhs| over the state, relative to max(1, |J|).
template <class F, class G> double jacobian_error(F rhs, G jac, std::vector<double> y, double t) {
    const std::size_t n = y.size();
    std::vector<double> J(n * n), fp(n), fm(n);
    jac(t, y.data(), J.data());
    double worst = 0;
    for (std::size_t c = 0; c < n; ++c) {
        const double e = 1e-6 * std::max(1.0, std::abs(y[c])), keep = y[c];
        y[c] = keep + e;
        rhs(t, y.data(), fp.data());
        y[c] = keep - e;
        rhs(t, y.data(), fm.data());
        y[c] = keep;
        for (std::size_t r = 0; r < n; ++r)
            worst = std::max(worst, std::abs(J[r * n + c] - (fp[r] - fm[r]) / (2 * e)) /
                                        std::max(1.0, std::abs(J[r * n + c])));
    }
    return worst;
}

} // namespace

TEST_CASE("torque-driven wheels: kernels against Newton-Euler written by hand, three skewed "
          "wheels",
          "[emit][wheels][torque]") {
    const truth g;
    const lag::params<double> pl;
    const ham::params<double> ph;
    const bod::params<double> pb;
    REQUIRE(lag::state_size == 9);
    REQUIRE(std::string(lag::state_names[6]) == "p_w1");
    REQUIRE(bod::state_size == 10);     // q (the torques need the angles), omega, p_w1..3
    REQUIRE(lag::parameter_count == 6); // p_w1..3 are states, not parameters
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-2, 2), ang(0, 6.283185307179586), th(0.3, 2.8);
    double worst_body = 0, worst_pdot = 0, worst_lag = 0, worst_qdot = 0, worst_ham = 0,
           worst_jac = 0, worst_energy = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const double t = 0.37 * trial;
        std::vector<double> y{ang(rng), th(rng), ang(rng), u(rng), u(rng),
                              u(rng),   u(rng),  u(rng),   u(rng)};
        const double* p = y.data() + 6;
        const Eigen::Vector3d w = omega_of(y.data(), y.data() + 3);
        const std::array<double, 3> tau = g.tau(t, y.data(), y[3], w);
        const Eigen::Vector3d wd = g.omega_dot(w, p, tau);
        // body form: y = (q, omega, p)
        std::vector<double> yb(10), fb(10);
        bod::quaternion_from_angles(y.data(), yb.data());
        for (int i = 0; i < 3; ++i)
            yb[4 + i] = w[i], yb[7 + i] = p[i];
        bod::rhs(t, yb.data(), fb.data(), pb);
        for (int i = 0; i < 3; ++i) {
            worst_body = std::max(worst_body, std::abs(fb[4 + i] - wd[i]));
            worst_pdot = std::max(worst_pdot, std::abs(fb[7 + i] - tau[i]));
        }
        // Lagrangian form: p' exactly, d/dt omega(q, q_dot) along its flow
        std::vector<double> fl(9), yp = y, ym = y;
        lag::rhs(t, y.data(), fl.data(), pl);
        for (int i = 0; i < 3; ++i)
            worst_pdot = std::max(worst_pdot, std::abs(fl[6 + i] - tau[i]));
        const double e = 1e-5;
        for (int i = 0; i < 9; ++i)
            yp[i] += e * fl[i], ym[i] -= e * fl[i];
        const Eigen::Vector3d lwd =
            (omega_of(yp.data(), yp.data() + 3) - omega_of(ym.data(), ym.data() + 3)) / (2 * e);
        worst_lag = std::max(worst_lag, (lwd - wd).cwiseAbs().maxCoeff());
        // Hamiltonian form at p_q = J^T (I omega + h), by hand
        const Eigen::Vector3d l = g.I * w + g.h(p);
        const double st = std::sin(y[1]), ct = std::cos(y[1]), sp = std::sin(y[2]),
                     cp = std::cos(y[2]);
        std::vector<double> yh{y[0],
                               y[1],
                               y[2],
                               st * sp * l[0] + st * cp * l[1] + ct * l[2],
                               cp * l[0] - sp * l[1],
                               l[2],
                               p[0],
                               p[1],
                               p[2]};
        std::vector<double> fh(9), mp(3), mm(3);
        ham::rhs(t, yh.data(), fh.data(), ph);
        lag::momenta(yp.data(), mp.data(), pl);
        lag::momenta(ym.data(), mm.data(), pl);
        for (int i = 0; i < 3; ++i) {
            worst_qdot = std::max(worst_qdot, std::abs(fh[i] - y[3 + i]));
            worst_pdot = std::max(worst_pdot, std::abs(fh[6 + i] - tau[i]));
            worst_ham = std::max(worst_ham, std::abs(fh[3 + i] - (mp[i] - mm[i]) / (2 * e)));
        }
        // energy: 1/2 omega . I omega + sum p_k^2 / (2 J)
        const double E = w.dot(g.I * w) / 2 + (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / 0.2;
        worst_energy = std::max({worst_energy, std::abs(lag::energy(y.data(), pl) - E),
                                 std::abs(ham::energy(yh.data(), ph) - E),
                                 std::abs(bod::energy(yb.data(), pb) - E)});
        worst_jac = std::max(
            {worst_jac,
             jacobian_error(
                 [&](double s, const double* z, double* f) { lag::rhs(s, z, f, pl); },
                 [&](double s, const double* z, double* J) { lag::jacobian(s, z, J, pl); }, y, t),
             jacobian_error(
                 [&](double s, const double* z, double* f) { ham::rhs(s, z, f, ph); },
                 [&](double s, const double* z, double* J) { ham::jacobian(s, z, J, ph); }, yh, t),
             jacobian_error(
                 [&](double s, const double* z, double* f) { bod::rhs(s, z, f, pb); },
                 [&](double s, const double* z, double* J) { bod::jacobian(s, z, J, pb); }, yb,
                 t)});
    }
    CHECK(worst_body < 2e-14);   // observed 1.8e-15
    CHECK(worst_pdot < 5e-15);   // observed 4.4e-16
    CHECK(worst_lag < 3e-8);     // observed 2.8e-9: central differences
    CHECK(worst_qdot < 3e-14);   // observed 2.4e-15
    CHECK(worst_ham < 6e-8);     // observed 5.8e-9: central differences
    CHECK(worst_energy < 7e-14); // observed 7.1e-15
    CHECK(worst_jac < 4e-8);     // observed 3.3e-9: central differences
}
