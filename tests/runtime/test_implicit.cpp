// Implicit and linearly implicit methods: the implicit midpoint rule (order 2, bounded energy
// error over long runs, Newton failure as a status) and RODAS4 (order 4, L-stability, stiff
// problems in far fewer steps than an explicit method).
// Set ROTGEN_VERBOSE=1 to print the measured slopes, errors and step counts.
#include <catch2/catch.hpp>

#include "integrate/integrate.hpp"
#include "steppers/dop853.hpp"
#include "steppers/dopri5.hpp"
#include "steppers/implicit_midpoint.hpp"
#include "steppers/rosenbrock.hpp"

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace rotgen;

namespace {

bool verbose() {
    return std::getenv("ROTGEN_VERBOSE") != nullptr;
}

// Least-squares slope of log(e) against log(h).
double fit_slope(const std::vector<double>& h, const std::vector<double>& e) {
    const double n = double(h.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < h.size(); ++i) {
        const double x = std::log(h[i]), y = std::log(e[i]);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

void report(const char* what, const std::vector<double>& h, const std::vector<double>& e,
            double slope) {
    if (!verbose()) return;
    std::printf("%s: slope %.3f;", what, slope);
    for (std::size_t i = 0; i < h.size(); ++i)
        std::printf(" h=%.4g err=%.3e", h[i], e[i]);
    std::printf("\n");
}

// Pendulum q'' = −sin q as y = (q, p): H = p²/2 − cos q.
auto pendulum() {
    return make_system<double, 2>(
        [](double, const double* y, double* d) {
            d[0] = y[1];
            d[1] = -std::sin(y[0]);
        },
        [](double, const double* y, double* j) {
            j[0] = 0, j[1] = 1;
            j[2] = -std::cos(y[0]), j[3] = 0;
        });
}
double pendulum_energy(const Eigen::Vector2d& y) {
    return 0.5 * y[1] * y[1] - std::cos(y[0]);
}

// Exact pendulum from rest at q0: with k = sin(q0/2), K = K(k),
//   q(t) = 2 asin(k sn(K − t, k)),  p(t) = q'(t) = −2k cn(K − t, k)
// (q(0) = 2 asin(k sn K) = q0; differentiate: q' = −2k cn dn / sqrt(1 − k² sn²) = −2k cn).
Eigen::Vector2d pendulum_exact(double q0, double t) {
    const double k = std::sin(q0 / 2), kk = boost::math::ellint_1(k);
    double cn, dn;
    const double sn = boost::math::jacobi_elliptic(k, kk - t, &cn, &dn);
    return {2 * std::asin(k * sn), -2 * k * cn};
}

} // namespace

// ---- implicit midpoint
// ----------------------------------------------------------------------------

TEST_CASE("implicit midpoint converges with order 2 on the pendulum", "[midpoint][order]") {
    const auto sys = pendulum();
    const double q0 = 1.0;
    std::vector<double> hs = {0.1, 0.05, 0.025, 0.0125}, errs;
    for (double h : hs) {
        implicit_midpoint<double> m;
        m.step = h;
        Eigen::Vector2d y(q0, 0.0);
        const auto r = integrate(sys, m, 0.0, y, 10.0);
        REQUIRE(r.ok());
        errs.push_back((y - pendulum_exact(q0, 10.0)).cwiseAbs().maxCoeff());
    }
    const double s = fit_slope(hs, errs);
    report("implicit midpoint pendulum", hs, errs, s);
    CHECK(s == Approx(2.0).margin(0.3));
}

TEST_CASE("implicit midpoint keeps the energy error bounded over 1e5 steps while DOPRI5 drifts",
          "[midpoint][dopri5][energy]") {
    // Pendulum from rest at q0 = 1 (period 6.7), h = 0.1, 1e5 steps to t = 1e4 (~1500 periods).
    // The midpoint rule is symplectic: it conserves a modified energy H + O(h²) exactly, so
    // |H(y_n) − H(y_0)| stays O(h²) for all n (Hairer–Lubich–Wanner, GNI, IX.8) — no drift.
    // DOPRI5 at a loose tolerance is not: its energy error grows linearly in t.
    const auto sys = pendulum();
    const double h = 0.1, t_end = 1e4, h0 = pendulum_energy(Eigen::Vector2d(1.0, 0.0));
    std::vector<double> times;
    for (int i = 1; i <= 10000; ++i)
        times.push_back(double(i));
    auto energy_errors = [&](const auto& method, double& first, double& last, step_stats& stats) {
        Eigen::Vector2d y(1.0, 0.0);
        first = last = 0;
        const auto r =
            integrate(sys, method, 0.0, y, times, [&](double t, const Eigen::Vector2d& yt) {
                const double e = std::abs(pendulum_energy(yt) - h0);
                if (t <= 0.1 * t_end) first = std::max(first, e);
                if (t >= 0.9 * t_end) last = std::max(last, e);
            });
        REQUIRE(r.ok());
        stats = r.stats;
    };
    implicit_midpoint<double> mid;
    mid.step = h;
    double mid_first, mid_last, dp_first, dp_last;
    step_stats mid_stats, dp_stats;
    energy_errors(mid, mid_first, mid_last, mid_stats);
    CHECK(mid_stats.accepted == 100000);
    dopri5<double> dp(1e-4, 1e-4);
    energy_errors(dp, dp_first, dp_last, dp_stats);
    if (verbose())
        std::printf(
            "energy error |H - H0|, first/last 10%% of t in [0, 1e4]: midpoint h=0.1 %.3e / %.3e "
            "(%zu f, %zu J, %zu LU) | dopri5 rtol 1e-4 %.3e / %.3e (%zu steps)\n",
            mid_first, mid_last, mid_stats.rhs_evals, mid_stats.jac_evals, mid_stats.factorisations,
            dp_first, dp_last, dp_stats.steps);
    // bounded: O(h²) — the leading term of the modified Hamiltonian of the midpoint rule is
    // h²/24·(f_q² p² − …) with |q| <= 1, |p| <= 2 sin(1/2) here, i.e. a constant below 0.1 —
    // and no growth from the first to the last tenth of the run
    CHECK(mid_last <= 0.1 * h * h);
    CHECK(mid_last <= 1.5 * mid_first);
    // drift: DOPRI5's error grows (roughly linearly: ~10× from t <= 1e3 to t >= 9e3) and ends
    // far above the midpoint rule's bound
    CHECK(dp_last >= 5 * dp_first);
    CHECK(dp_last >= 10 * mid_last);
}

TEST_CASE("implicit midpoint conserves the quadratic energy of the harmonic oscillator to rounding",
          "[midpoint][energy]") {
    // Quadratic invariants are conserved exactly by the midpoint rule; with the Newton iteration
    // converged to ~10·eps only rounding remains (~sqrt(n)·eps … n·eps for n = 1e5 steps).
    const auto sys = make_system<double, 2>(
        [](double, const double* y, double* d) {
            d[0] = y[1];
            d[1] = -y[0];
        },
        [](double, const double*, double* j) { j[0] = 0, j[1] = 1, j[2] = -1, j[3] = 0; });
    implicit_midpoint<double> m;
    m.step = 0.1;
    Eigen::Vector2d y(1.0, 0.0);
    double worst = 0;
    std::vector<double> times;
    for (int i = 1; i <= 1000; ++i)
        times.push_back(10.0 * i);
    const auto r = integrate(sys, m, 0.0, y, times, [&](double, const Eigen::Vector2d& yt) {
        worst = std::max(worst, std::abs(yt.squaredNorm() - 1.0));
    });
    REQUIRE(r.ok());
    if (verbose()) std::printf("midpoint oscillator 1e5 steps: max |2H - 1| = %.3e\n", worst);
    CHECK(worst < 1e5 * std::numeric_limits<double>::epsilon());
}

TEST_CASE("implicit midpoint reports Newton failure as a status, at the last good state",
          "[midpoint][status]") {
    // y' = y², y(0) = 1, h = 1: the midpoint equation z = 1 + z²/2 has no real root
    const auto sys =
        make_system<double, 1>([](double, const double* y, double* d) { d[0] = y[0] * y[0]; },
                               [](double, const double* y, double* j) { j[0] = 2 * y[0]; });
    implicit_midpoint<double> m;
    m.step = 1.0;
    Eigen::Matrix<double, 1, 1> y(1.0);
    const auto r = integrate(sys, m, 0.0, y, 3.0);
    CHECK(r.code == status::newton_failure);
    CHECK(r.t == 0.0);
    CHECK(y[0] == 1.0);
    CHECK_FALSE(r.message.empty());
    CHECK(r.stats.factorisations == 2); // simplified Newton, then once more with a fresh Jacobian
}

TEST_CASE("implicit midpoint without an analytic Jacobian uses finite differences", "[midpoint]") {
    const auto sys = make_system<double, 2>([](double, const double* y, double* d) {
        d[0] = y[1];
        d[1] = -std::sin(y[0]);
    });
    static_assert(!has_jacobian_v<decltype(sys), double>);
    implicit_midpoint<double> m;
    m.step = 0.05;
    Eigen::Vector2d y(1.0, 0.0);
    const auto r = integrate(sys, m, 0.0, y, 10.0);
    REQUIRE(r.ok());
    CHECK(r.stats.jac_evals == r.stats.accepted);
    CHECK((y - pendulum_exact(1.0, 10.0)).cwiseAbs().maxCoeff() <
          1e-2); // O(h²) as with the exact J
}

// ---- RODAS4 ------------------------------------------------------------------------------------

TEST_CASE("RODAS4 converges with order 4 on a nonlinear non-autonomous problem",
          "[rodas4][order]") {
    // Manufactured solution u(t) = (sin t, cos(2t)/2 + 1) of y' = g(y) + u'(t) − g(u(t)),
    // g(y) = (−y1 y2, y1² − y2): nonlinear in y, explicitly time dependent (exercises the h γ_i f_t
    // terms; f_t by central differences).
    auto g = [](double y1, double y2, double* out) {
        out[0] = -y1 * y2;
        out[1] = y1 * y1 - y2;
    };
    const auto sys = make_system<double, 2>(
        [g](double t, const double* y, double* d) {
            const double u1 = std::sin(t), u2 = std::cos(2 * t) / 2 + 1;
            double gy[2], gu[2];
            g(y[0], y[1], gy);
            g(u1, u2, gu);
            d[0] = gy[0] + std::cos(t) - gu[0];
            d[1] = gy[1] - std::sin(2 * t) - gu[1];
        },
        [](double, const double* y, double* j) {
            j[0] = -y[1], j[1] = -y[0];
            j[2] = 2 * y[0], j[3] = -1;
        });
    std::vector<double> hs = {0.2, 0.1, 0.05, 0.025}, errs;
    for (double h : hs) {
        rodas4<double> m;
        m.fixed_step = h;
        Eigen::Vector2d y(0.0, 1.5);
        REQUIRE(integrate(sys, m, 0.0, y, 4.0).ok());
        errs.push_back(
            std::max(std::abs(y[0] - std::sin(4.0)), std::abs(y[1] - std::cos(8.0) / 2 - 1)));
    }
    const double s = fit_slope(hs, errs);
    report("rodas4 manufactured", hs, errs, s);
    CHECK(s == Approx(4.0).margin(0.3));
}

TEST_CASE("RODAS4 is L-stable: R(z) -> 0 as z -> -infinity, |R(z)| < 1 on the negative axis",
          "[rodas4]") {
    for (double z : {-0.5, -5.0, -50.0, -500.0, -1e4, -1e8, -1e12}) {
        const auto sys =
            make_system<double, 1>([z](double, const double* y, double* d) { d[0] = z * y[0]; },
                                   [z](double, const double*, double* j) { j[0] = z; });
        rodas4<double> m;
        m.fixed_step = 1.0; // one step, h λ = z
        m.autonomous = true;
        Eigen::Matrix<double, 1, 1> y(1.0);
        REQUIRE(integrate(sys, m, 0.0, y, 1.0).ok());
        const double r = y[0]; // = R(z)
        CHECK(std::abs(r) < 1.0);
        if (z <= -1e4) CHECK(std::abs(r) <= 100.0 / std::abs(z)); // R(z) = O(1/z): stiffly accurate
    }
}

TEST_CASE("RODAS4 on a stiff linear system: far fewer steps than DOPRI5, exact solution matched",
          "[rodas4][stiff]") {
    // y' = A y, A = [[−(1+L)/2, (L−1)/2], [(L−1)/2, −(1+L)/2]] with eigenvalues −1 (eigenvector
    // (1, 1)) and −L = −1e6 (eigenvector (1, −1)); y(0) = (2, 0) = (1, 1) + (1, −1):
    //   y(t) = e^{−t} (1, 1) + e^{−L t} (1, −1).
    const double L = 1e6;
    const double a = -(1 + L) / 2, b = (L - 1) / 2;
    const auto sys = make_system<double, 2>(
        [a, b](double, const double* y, double* d) {
            d[0] = a * y[0] + b * y[1];
            d[1] = b * y[0] + a * y[1];
        },
        [a, b](double, const double*, double* j) { j[0] = a, j[1] = b, j[2] = b, j[3] = a; });
    auto exact = [L](double t) {
        const double s = std::exp(-t), f = std::exp(-L * t);
        return Eigen::Vector2d(s + f, s - f);
    };
    std::vector<double> times;
    for (double t : {1e-7, 1e-6, 1e-5, 1e-3, 0.1, 0.5, 1.0})
        times.push_back(t);
    auto run = [&](const auto& method, double& err) {
        Eigen::Vector2d y(2.0, 0.0);
        err = 0;
        const auto r =
            integrate(sys, method, 0.0, y, times, [&](double t, const Eigen::Vector2d& yt) {
                err = std::max(err, (yt - exact(t)).cwiseAbs().maxCoeff());
            });
        REQUIRE(r.ok());
        return r.stats;
    };
    rodas4<double> ro(1e-6, 1e-8);
    ro.autonomous = true;
    dopri5<double> dp(1e-6, 1e-8);
    double ro_err, dp_err;
    const step_stats ro_stats = run(ro, ro_err), dp_stats = run(dp, dp_err);
    if (verbose())
        std::printf("stiff linear (lambda = -1, -1e6) on [0, 1], rtol 1e-6: rodas4 %zu steps (%zu "
                    "f, %zu J, %zu LU) "
                    "err %.3e | dopri5 %zu steps (%zu f) err %.3e\n",
                    ro_stats.steps, ro_stats.rhs_evals, ro_stats.jac_evals, ro_stats.factorisations,
                    ro_err, dp_stats.steps, dp_stats.rhs_evals, dp_err);
    // DOPRI5 is held by stability (|h λ| <= 3.3) to ~3e5 steps over t = 1; RODAS4 by accuracy only
    CHECK(ro_stats.steps * 1000 < dp_stats.steps);
    // a dissipative problem damps earlier errors, so the global error stays at the level of the
    // local tolerance: rtol·|y| + atol ~ 1e-6; allow 10×
    CHECK(ro_err < 1e-5);
}

TEST_CASE("RODAS4 on Robertson's chemical kinetics: conserves mass, agrees with DOP853",
          "[rodas4][stiff]") {
    //   y1' = −0.04 y1 + 1e4 y2 y3,  y2' = 0.04 y1 − 1e4 y2 y3 − 3e7 y2²,  y3' = 3e7 y2²
    const auto sys = make_system<double, 3>(
        [](double, const double* y, double* d) {
            d[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
            d[2] = 3e7 * y[1] * y[1];
            d[1] = -d[0] - d[2];
        },
        [](double, const double* y, double* j) {
            j[0] = -0.04, j[1] = 1e4 * y[2], j[2] = 1e4 * y[1];
            j[6] = 0, j[7] = 6e7 * y[1], j[8] = 0;
            j[3] = -j[0] - j[6], j[4] = -j[1] - j[7], j[5] = -j[2] - j[8];
        });
    rodas4<double> ro(1e-8, 1e-14);
    ro.autonomous = true;
    Eigen::Vector3d y(1.0, 0.0, 0.0);
    double mass_err = 0;
    std::vector<double> times = {1e-3, 0.1, 1.0, 10.0, 40.0};
    const auto r = integrate(sys, ro, 0.0, y, times, [&](double, const Eigen::Vector3d& yt) {
        mass_err = std::max(mass_err, std::abs(yt.sum() - 1.0));
    });
    REQUIRE(r.ok());
    // reference: DOP853 at rtol 1e-12 (explicit, stability-limited, but accurate)
    dop853<double> ref(1e-12, 1e-18);
    Eigen::Vector3d yr(1.0, 0.0, 0.0);
    const auto rr = integrate(sys, ref, 0.0, yr, 40.0);
    REQUIRE(rr.ok());
    if (verbose())
        std::printf("robertson t=40: rodas4 %zu steps, y = (%.10f, %.6e, %.10f), mass err %.2e | "
                    "dop853 %zu steps, "
                    "y = (%.10f, %.6e, %.10f)\n",
                    r.stats.steps, y[0], y[1], y[2], mass_err, rr.stats.steps, yr[0], yr[1], yr[2]);
    // linear invariants are preserved by Rosenbrock methods with the exact Jacobian: rounding only
    CHECK(mass_err < 1e-13);
    // agreement to the tolerance (rtol 1e-8, global error of a dissipative problem ~ rtol)
    CHECK(y[0] == Approx(yr[0]).epsilon(1e-7));
    CHECK(y[1] == Approx(yr[1]).epsilon(1e-6));
    CHECK(y[2] == Approx(yr[2]).epsilon(1e-7));
    // DOP853 is stability-limited (h |λ_max| <= ~6 with λ_max ~ −1e4 late in the run)
    CHECK(r.stats.steps * 10 < rr.stats.steps);
}
