// The Taylor method in lanes (steppers/taylor_lanes.hpp on lanes.hpp's lane_taylor_system), on the
// checked-in heavy top with Taylor coefficients. The lane kernels here apply the scalar generated
// functions to each lane, so a lane differs from its member's scalar run only by the shared order
// and step:
// - lanes that all hold one member take its scalar run's steps and samples bit for bit;
// - lanes of different members take the smallest of their steps: at least as many steps as the
//   most demanding member alone, every lane within the tolerance of its scalar run;
// - a lane whose coefficients are not finite fails alone; a stopped lane stays where it is.
#include <catch2/catch.hpp>

#include "integrate/integrate.hpp"
#include "lanes.hpp"
#include "steppers/taylor.hpp"
#include "taylor_system.hpp"

#include "heavy_top_taylor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

using namespace rotgen;
namespace heavy_top = rotgen::models::heavy_top_taylor;

namespace {

// One heavy top member: theta0 and psi_dot0 (phi = psi = 0, phi_dot = theta_dot = 0), its h.
struct member {
    double theta, psi_dot, h;
};

heavy_top::params<double> params_of(const member& m) {
    heavy_top::params<double> p;
    p.h = m.h;
    return p;
}

// The members' lanes: rhs and taylor of the generated header on each lane in turn, component c
// of lane l at y[c W + l], coefficient k of component i at c[(i (order + 1) + k) W + l]. With
// Reports, taylor also says whether every coefficient it wrote is finite, as the batch kernels
// of `sweep --lanes` do (the system then takes its word instead of looking).
template <bool Reports = false> auto heavy_top_lanes(const std::vector<member>& members) {
    const std::size_t w = members.size(), n = heavy_top::state_size;
    const auto rhs = [members, w, n](double t, const double* y, double* d) {
        for (std::size_t l = 0; l < w; ++l) {
            std::array<double, heavy_top::state_size> yl{}, dl{};
            for (std::size_t c = 0; c < n; ++c)
                yl[c] = y[c * w + l];
            heavy_top::rhs(t, yl.data(), dl.data(), params_of(members[l]));
            for (std::size_t c = 0; c < n; ++c)
                d[c * w + l] = dl[c];
        }
    };
    const auto coefficients = [members, w, n](double t, double* c, int order) {
        const std::size_t m = static_cast<std::size_t>(order) + 1;
        std::vector<double> cl(heavy_top::taylor_series * m);
        bool finite = true;
        for (std::size_t l = 0; l < w; ++l) {
            for (std::size_t i = 0; i < n; ++i)
                cl[i * m] = c[i * m * w + l];
            heavy_top::taylor(t, cl.data(), order, params_of(members[l]));
            for (std::size_t i = 0; i < n; ++i)
                for (std::size_t k = 1; k < m; ++k)
                    finite = std::isfinite(c[(i * m + k) * w + l] = cl[i * m + k]) && finite;
        }
        if constexpr (Reports) return finite;
    };
    return lane_taylor_system<double, decltype(rhs), decltype(coefficients)>(rhs, coefficients, n,
                                                                             w);
}

Eigen::VectorXd lane_start(const std::vector<member>& members) {
    const std::size_t w = members.size();
    Eigen::VectorXd y = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(6 * w));
    for (std::size_t l = 0; l < w; ++l) {
        y[static_cast<Eigen::Index>(w + l)] = members[l].theta;
        y[static_cast<Eigen::Index>(5 * w + l)] = members[l].psi_dot;
    }
    return y;
}

std::vector<double> sample_times() {
    std::vector<double> t;
    for (int i = 0; i <= 40; ++i)
        t.push_back(0.05 * i);
    return t;
}

// The member's scalar run: its samples (one state per sample time) and result.
struct scalar_run {
    std::vector<Eigen::Matrix<double, 6, 1>> samples;
    integration_result<double> res;
};

scalar_run run_alone(const member& m, const taylor<double>& method) {
    auto sys = ROTGEN_GENERATED_TAYLOR_SYSTEM(heavy_top, double);
    sys.params = params_of(m);
    Eigen::Matrix<double, 6, 1> y;
    y << 0, m.theta, 0, 0, 0, m.psi_dot;
    scalar_run r;
    r.res =
        integrate(sys, method, 0.0, y, sample_times(),
                  [&](double, const Eigen::Matrix<double, 6, 1>& v) { r.samples.push_back(v); });
    return r;
}

taylor<double> method_of(double tol) {
    taylor<double> m;
    m.rtol = m.atol = tol;
    return m;
}

} // namespace

TEST_CASE("taylor lanes of one member take its scalar run's steps bit for bit", "[taylor][lanes]") {
    const member one{0.5, 30, 0.1};
    const taylor<double> method = method_of(1e-12);
    const scalar_run alone = run_alone(one, method);
    REQUIRE(alone.res.ok());
    // 3 lanes take the stepper's loops over a run-time lane count, 4 and 8 its compile-time ones
    for (const std::size_t w : {3, 4, 8}) {
        const std::vector<member> members(w, one);
        const auto sys = heavy_top_lanes(members);
        Eigen::VectorXd y = lane_start(members);
        std::vector<Eigen::VectorXd> samples;
        const auto res = integrate(sys, method, 0.0, y, sample_times(),
                                   [&](double, const Eigen::VectorXd& v) { samples.push_back(v); });
        REQUIRE(res.ok());
        CHECK(res.stats.steps == alone.res.stats.steps);
        CHECK(res.stats.rhs_evals == alone.res.stats.rhs_evals);
        REQUIRE(samples.size() == alone.samples.size());
        for (std::size_t s = 0; s < samples.size(); ++s)
            for (std::size_t l = 0; l < w; ++l)
                for (std::size_t c = 0; c < 6; ++c)
                    REQUIRE(samples[s][static_cast<Eigen::Index>(c * w + l)] ==
                            alone.samples[s][static_cast<Eigen::Index>(c)]);
    }
}

TEST_CASE("taylor lanes take the smallest of their steps and each meets the tolerance",
          "[taylor][lanes]") {
    const std::vector<member> members{{0.5, 30, 0.1}, {1.2, 5, 0.3}, {0.2, 60, 0.1}, {0.9, 0, 0.2}};
    const double tol = 1e-10;
    const taylor<double> method = method_of(tol);
    const auto sys = heavy_top_lanes(members);
    Eigen::VectorXd y = lane_start(members);
    const auto res = integrate(sys, method, 0.0, y, 2.0);
    REQUIRE(res.ok());
    std::size_t most = 0, least = res.stats.steps;
    double worst = 0;
    for (std::size_t l = 0; l < members.size(); ++l) {
        const scalar_run alone = run_alone(members[l], method);
        REQUIRE(alone.res.ok());
        most = std::max(most, alone.res.stats.steps);
        least = std::min(least, alone.res.stats.steps);
        for (Eigen::Index c = 0; c < 6; ++c) {
            const double x = alone.samples.back()[c];
            const double d = std::abs(y[c * 4 + static_cast<Eigen::Index>(l)] - x);
            worst = std::max(worst, d / std::max(std::abs(x), 1.0));
        }
    }
    // the fastest spinner (psi_dot 60) sets the step: observed 53 steps against its 53 alone
    // and 12 for the slowest member alone
    CHECK(res.stats.steps >= most);
    CHECK(res.stats.steps <= most + most / 10);
    CHECK(least < most / 2);
    // observed 7.8e-11: the runs differ by their own errors (each within the tolerance)
    CHECK(worst < 8e-10);
}

TEST_CASE("a taylor lane whose coefficients are not finite fails alone", "[taylor][lanes]") {
    // lane 1 starts at theta = 0, where the Lagrangian form divides by sin theta
    const std::vector<member> members{{0.5, 30, 0.1}, {0.0, 30, 0.1}, {0.7, 10, 0.1}};
    const taylor<double> method = method_of(1e-12);
    auto sys = heavy_top_lanes(members);
    sys.stop(2); // a stopped lane stays where it is
    Eigen::VectorXd y = lane_start(members);
    const Eigen::VectorXd y0 = y;
    const auto res = integrate(sys, method, 0.0, y, 2.0);
    REQUIRE(res.ok());
    CHECK(sys.failed_lane(1));
    CHECK(!sys.failed_lane(0));
    CHECK(!sys.failed_lane(2));
    CHECK(sys.is_live(0));
    const scalar_run alone = run_alone(members[0], method);
    REQUIRE(alone.res.ok());
    // lane 0 alone chooses every step: its scalar run, bit for bit
    CHECK(res.stats.steps == alone.res.stats.steps);
    for (Eigen::Index c = 0; c < 6; ++c) {
        CHECK(y[c * 3] == alone.samples.back()[c]);
        CHECK(y[c * 3 + 1] == y0[c * 3 + 1]);
        CHECK(y[c * 3 + 2] == y0[c * 3 + 2]);
    }
}

TEST_CASE("a taylor lane fails alone when the coefficients' function reports them not finite",
          "[taylor][lanes]") {
    // every lane live, so the system takes the function's word; lane 1 at theta = 0 as above
    const std::vector<member> members{{0.5, 30, 0.1}, {0.0, 30, 0.1}, {0.7, 10, 0.1}};
    auto sys = heavy_top_lanes<true>(members);
    Eigen::VectorXd y = lane_start(members);
    const Eigen::VectorXd y0 = y;
    const auto res = integrate(sys, method_of(1e-12), 0.0, y, 2.0);
    REQUIRE(res.ok());
    CHECK(sys.failed_lane(1));
    CHECK(!sys.failed_lane(0));
    CHECK(!sys.failed_lane(2));
    CHECK(y.allFinite());
    for (Eigen::Index c = 0; c < 6; ++c)
        CHECK(y[c * 3 + 1] == y0[c * 3 + 1]); // a failed lane stays where it failed
}

TEST_CASE("a taylor lane at rest leaves the step to the moving lanes, bit for bit",
          "[taylor][lanes]") {
    // lane 1 has no torque (h = 0) and no rates: every coefficient past order 0 is 0, so its
    // radius is infinite and the step is lane 0's alone (the lanes' least quotient ignores it)
    const std::vector<member> members{{0.5, 30, 0.1}, {0.9, 0, 0.0}};
    const taylor<double> method = method_of(1e-12);
    const auto sys = heavy_top_lanes(members);
    Eigen::VectorXd y = lane_start(members);
    const Eigen::VectorXd y0 = y;
    const auto res = integrate(sys, method, 0.0, y, 2.0);
    REQUIRE(res.ok());
    const scalar_run alone = run_alone(members[0], method);
    REQUIRE(alone.res.ok());
    CHECK(res.stats.steps == alone.res.stats.steps);
    for (Eigen::Index c = 0; c < 6; ++c) {
        CHECK(y[c * 2] == alone.samples.back()[c]);
        CHECK(y[c * 2 + 1] == y0[c * 2 + 1]);
    }
}
