// Independent routes to the same motion: the body form (Euler's equations with a quaternion) and
// the Hamiltonian form against the Lagrangian form, away from theta = 0; quaternion helpers; Eigen
// array batches against scalar calls.
#include "kernels.hpp"

#include "units.hpp"

#include <Eigen/Core>
#include <catch2/catch.hpp>

#include <cmath>

using namespace rotgen_test;

namespace {

const std::vector<std::string>& models() {
    static const std::vector<std::string> m{"free_asymmetric_top", "heavy_top", "full_tensor_top",
                                            "damped_driven_top"};
    return m;
}

// d/dt g(y(t)) along the flow of `lag` by central differences.
template <class G>
std::vector<double> along_flow(const kernel& lag, double t, const std::vector<double>& y,
                               std::size_t m, G g) {
    std::vector<double> f(lag.n), yp = y, ym = y, gp(m), gm(m), d(m);
    lag.rhs(t, y.data(), f.data());
    const double h = 1e-5;
    for (std::size_t i = 0; i < lag.n; ++i)
        yp[i] += h * f[i], ym[i] -= h * f[i];
    g(yp.data(), gp.data());
    g(ym.data(), gm.data());
    for (std::size_t i = 0; i < m; ++i)
        d[i] = (gp[i] - gm[i]) / (2 * h);
    return d;
}

double wrap(double a) {
    const double two_pi = 6.283185307179586;
    a = std::fmod(a, two_pi);
    return a < 0 ? a + two_pi : a;
}

} // namespace

TEST_CASE("the body form moves as the Euler-angle form does, away from theta = 0", "[emit][body]") {
    for (const std::string& m : models()) {
        const kernel& lag = find_kernel(m);
        const kernel& body = find_kernel(m + "_body");
        INFO("model " << m);
        REQUIRE(body.n == 7);
        std::mt19937 rng(21);
        for (int trial = 0; trial < 25; ++trial) {
            const std::vector<double> y = random_state(lag, rng);
            const double t = 0.3 * trial;
            std::vector<double> yb(7), fb(7), w(3), A(9), Ab(9);
            body.quaternion_from_angles(y.data(), yb.data());
            const double norm = 0.5 + 0.1 * trial; // any norm
            for (int i = 0; i < 4; ++i)
                yb[i] *= norm;
            lag.omega(y.data(), w.data());
            for (int i = 0; i < 3; ++i)
                yb[4 + i] = w[i];
            body.rhs(t, yb.data(), fb.data());
            // omega_dot = d/dt omega(q, q_dot) along the Lagrangian motion
            const std::vector<double> wd =
                along_flow(lag, t, y, 3, [&](const double* z, double* o) { lag.omega(z, o); });
            for (int i = 0; i < 3; ++i)
                CHECK(fb[4 + i] == Approx(wd[i]).epsilon(1e-7).margin(1e-7));
            // q_dot = d/dt quaternion(angles(t))
            const std::vector<double> qd =
                along_flow(lag, t, y, 4,
                           [&](const double* z, double* o) { body.quaternion_from_angles(z, o); });
            for (int i = 0; i < 4; ++i)
                CHECK(fb[i] == Approx(norm * qd[i]).epsilon(1e-7).margin(1e-7));
            // same rotation, same energy, angles back from the quaternion
            lag.rotation(y.data(), A.data());
            body.rotation(yb.data(), Ab.data());
            for (int i = 0; i < 9; ++i)
                CHECK(Ab[i] == Approx(A[i]).epsilon(1e-13).margin(1e-13));
            CHECK(body.energy(yb.data()) == Approx(lag.energy(y.data())).epsilon(1e-12));
            double angles[3];
            body.angles_from_quaternion(yb.data(), angles);
            CHECK(wrap(angles[0]) == Approx(wrap(y[0])).margin(1e-12));
            CHECK(angles[1] == Approx(y[1]).margin(1e-12));
            CHECK(wrap(angles[2]) == Approx(wrap(y[2])).margin(1e-12));
        }
    }
}

TEST_CASE("the body form has no singularity at theta = 0 for gravity", "[emit][body]") {
    const kernel& body = find_kernel("full_tensor_top_body");
    const double angles[3] = {0.4, 0.0, 1.1};
    std::vector<double> y(7), f(7), J(49);
    body.quaternion_from_angles(angles, y.data());
    y[4] = 0.3, y[5] = -0.2, y[6] = 5.0;
    body.rhs(0.0, y.data(), f.data());
    body.jacobian(0.0, y.data(), J.data());
    for (double v : f)
        CHECK(std::isfinite(v));
    for (double v : J)
        CHECK(std::isfinite(v));
}

TEST_CASE("the Hamiltonian form moves as the Lagrangian form does", "[emit][hamiltonian]") {
    for (const std::string& m : models()) {
        const kernel& lag = find_kernel(m);
        const kernel& ham = find_kernel(m + "_hamiltonian");
        const kernel& sol = find_kernel(m + "_solve");
        INFO("model " << m);
        std::mt19937 rng(4);
        for (int trial = 0; trial < 25; ++trial) {
            const std::vector<double> y = random_state(lag, rng);
            const double t = 0.2 * trial;
            std::vector<double> f(6), fs(6), fh(6), yh(6), w(3), wh(3);
            lag.rhs(t, y.data(), f.data());
            sol.rhs(t, y.data(), fs.data());
            for (int i = 0; i < 6; ++i)
                CHECK(fs[i] == Approx(f[i]).epsilon(1e-10).margin(1e-10));
            for (int i = 0; i < 3; ++i)
                yh[i] = y[i];
            lag.momenta(y.data(), yh.data() + 3);
            ham.rhs(t, yh.data(), fh.data());
            for (int i = 0; i < 3; ++i)
                CHECK(fh[i] == Approx(y[3 + i]).epsilon(1e-11).margin(1e-11));
            const std::vector<double> pd =
                along_flow(lag, t, y, 3, [&](const double* z, double* o) { lag.momenta(z, o); });
            for (int i = 0; i < 3; ++i)
                CHECK(fh[3 + i] == Approx(pd[i]).epsilon(1e-7).margin(1e-7));
            CHECK(ham.energy(yh.data()) == Approx(lag.energy(y.data())).epsilon(1e-12));
            lag.omega(y.data(), w.data());
            ham.omega(yh.data(), wh.data());
            for (int i = 0; i < 3; ++i)
                CHECK(wh[i] == Approx(w[i]).epsilon(1e-12).margin(1e-12));
        }
    }
}

TEST_CASE("an Eigen array batch gives what scalar calls give", "[emit][scalar]") {
    using batch = Eigen::Array<double, 4, 1>;
    namespace ft = rotgen::models::full_tensor_top;
    namespace fb = rotgen::models::full_tensor_top_body;
    const kernel& lag = find_kernel("full_tensor_top");
    const kernel& body = find_kernel("full_tensor_top_body");
    std::mt19937 rng(8);
    std::vector<std::vector<double>> ys, yb;
    for (int b = 0; b < 4; ++b)
        ys.push_back(random_state(lag, rng)), yb.push_back(random_state(body, rng));
    {
        batch y[6], f[6], J[36];
        for (int i = 0; i < 6; ++i)
            for (int b = 0; b < 4; ++b)
                y[i][b] = ys[b][i];
        const ft::params<batch> p;
        const batch t = batch::Constant(0.5); // t's type fixes T: an Eigen expression would not do
        ft::rhs(t, y, f, p);
        ft::jacobian(t, y, J, p);
        const batch e = ft::energy(y, p);
        for (int b = 0; b < 4; ++b) {
            std::vector<double> fs(6), Js(36);
            lag.rhs(0.5, ys[b].data(), fs.data());
            lag.jacobian(0.5, ys[b].data(), Js.data());
            for (int i = 0; i < 6; ++i)
                CHECK(f[i][b] == fs[i]);
            for (int i = 0; i < 36; ++i)
                CHECK(J[i][b] == Js[i]);
            CHECK(e[b] == lag.energy(ys[b].data()));
        }
    }
    {
        batch y[7], f[7];
        for (int i = 0; i < 7; ++i)
            for (int b = 0; b < 4; ++b)
                y[i][b] = yb[b][i];
        const fb::params<batch> p;
        fb::rhs(batch(batch::Zero()), y, f, p);
        for (int b = 0; b < 4; ++b) {
            std::vector<double> fs(7);
            body.rhs(0.0, yb[b].data(), fs.data());
            for (int i = 0; i < 7; ++i)
                CHECK(f[i][b] == fs[i]);
        }
    }
}
