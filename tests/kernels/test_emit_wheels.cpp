// A gyrostat's generated kernels (models/momentum_wheels.yaml: a full tensor and three free wheels
// on skewed axes) against Newton-Euler written here from the convention, at random states:
//   I omega_dot + omega x (I omega + h) = -h_dot = 0,  h = sum_k p_k a_k,
//   p_k = J_k (a_k . omega + alpha_dot_k) constant (the parameters p_wheel1..3),
// I without the wheels' axial moments. The body form's omega_dot, the Lagrangian form's omega_dot
// along its flow, the Hamiltonian form's rates at the matching state (p = J^T (I omega + h)), and
// the energy T = 1/2 omega . I omega + sum_k p_k^2 / (2 J).
#include "kernels.hpp"

#include "units.hpp"

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include <cmath>

using namespace rotgen_test;

namespace {

struct gyrostat {
    Eigen::Matrix3d I;
    std::array<Eigen::Vector3d, 3> a;
    std::array<double, 3> p{0.7, -0.4, 1.1};
    double J = 0.1;
    // parameter values in the kernels' order: A B C D J p_wheel1 p_wheel2 p_wheel3
    std::vector<double> parameters() const { return {2, 3, 4.5, 0.2, J, p[0], p[1], p[2]}; }
    gyrostat() {
        I << 2, 0.2, 0, 0.2, 3, -0.2, 0, -0.2, 4.5;
        a = {Eigen::Vector3d(1, 0.2, 0).normalized(), Eigen::Vector3d(0, 1, 0.3).normalized(),
             Eigen::Vector3d(0.1, -0.2, 1).normalized()};
    }
    Eigen::Vector3d h() const { return p[0] * a[0] + p[1] * a[1] + p[2] * a[2]; }
    Eigen::Vector3d omega_dot(const Eigen::Vector3d& om) const {
        return I.lu().solve(-om.cross(I * om + h()));
    }
    double energy(const Eigen::Vector3d& om) const {
        return om.dot(I * om) / 2 + (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / (2 * J);
    }
};

// d/dt g(y(t)) along the flow of `k` by central differences.
template <class G>
std::vector<double> along_flow(const kernel& k, double t, const std::vector<double>& y,
                               std::size_t m, G g) {
    std::vector<double> f(k.n), yp = y, ym = y, gp(m), gm(m), d(m);
    k.rhs(t, y.data(), f.data());
    const double e = 1e-5;
    for (std::size_t i = 0; i < k.n; ++i)
        yp[i] += e * f[i], ym[i] -= e * f[i];
    g(t + e, yp.data(), gp.data());
    g(t - e, ym.data(), gm.data());
    for (std::size_t i = 0; i < m; ++i)
        d[i] = (gp[i] - gm[i]) / (2 * e);
    return d;
}

} // namespace

TEST_CASE("gyrostat kernels against Newton-Euler written by hand, three skewed wheels",
          "[emit][wheels]") {
    const gyrostat g;
    const kernel body = find_kernel("momentum_wheels_body").with_parameters(g.parameters());
    const kernel lag = find_kernel("momentum_wheels").with_parameters(g.parameters());
    const kernel ham = find_kernel("momentum_wheels_hamiltonian").with_parameters(g.parameters());
    REQUIRE(body.parameter_names.back() == "p_wheel3");
    std::mt19937 rng(5);
    double worst_body = 0, worst_lag = 0, worst_qdot = 0, worst_pdot = 0, worst_energy = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const std::vector<double> y = random_state(lag, rng);
        const double t = 0.37 * trial;
        std::vector<double> w(3), yb(body.n), fb(body.n);
        lag.omega(y.data(), w.data());
        const Eigen::Vector3d om(w[0], w[1], w[2]);
        const Eigen::Vector3d wd = g.omega_dot(om);
        // body form: y = (q, omega)
        body.quaternion_from_angles(y.data(), yb.data());
        for (std::size_t i = 0; i < 3; ++i)
            yb[body.n - 3 + i] = w[i];
        body.rhs(t, yb.data(), fb.data());
        for (std::size_t i = 0; i < 3; ++i)
            worst_body = std::max(worst_body, std::abs(fb[body.n - 3 + i] - wd[int(i)]));
        // Lagrangian form: d/dt omega(q, q_dot) along its flow
        const std::vector<double> lwd =
            along_flow(lag, t, y, 3, [&](double, const double* z, double* o) { lag.omega(z, o); });
        for (std::size_t i = 0; i < 3; ++i)
            worst_lag = std::max(worst_lag, std::abs(lwd[i] - wd[int(i)]));
        // Hamiltonian form at (q, p): q_dot as the Lagrangian state's, p_dot = d/dt p along the
        // Lagrangian flow; p = J^T (I omega + h) by hand
        std::vector<double> yh(6), fh(6), p(3);
        lag.momenta(y.data(), p.data());
        const double st = std::sin(y[1]), ct = std::cos(y[1]), sp = std::sin(y[2]),
                     cp = std::cos(y[2]);
        const Eigen::Vector3d l = g.I * om + g.h();
        const double ph[3] = {st * sp * l[0] + st * cp * l[1] + ct * l[2], cp * l[0] - sp * l[1],
                              l[2]};
        for (std::size_t i = 0; i < 3; ++i) {
            CHECK(p[i] == Approx(ph[i]).margin(1e-12));
            yh[i] = y[i], yh[3 + i] = p[i];
        }
        ham.rhs(t, yh.data(), fh.data());
        const std::vector<double> pd = along_flow(
            lag, t, y, 3, [&](double, const double* z, double* o) { lag.momenta(z, o); });
        for (std::size_t i = 0; i < 3; ++i) {
            worst_qdot = std::max(worst_qdot, std::abs(fh[i] - y[3 + i]));
            worst_pdot = std::max(worst_pdot, std::abs(fh[3 + i] - pd[i]));
        }
        worst_energy = std::max(worst_energy, std::abs(lag.energy(y.data()) - g.energy(om)));
        worst_energy = std::max(worst_energy, std::abs(ham.energy(yh.data()) - g.energy(om)));
    }
    CHECK(worst_body < 3e-14);   // observed 2.7e-15
    CHECK(worst_lag < 4e-8);     // observed 3.6e-9: central differences
    CHECK(worst_qdot < 3e-14);   // observed 3.1e-15
    CHECK(worst_pdot < 7e-8);    // observed 7.4e-9: central differences
    CHECK(worst_energy < 7e-14); // observed 7.1e-15
}
