// Lanes (lanes.hpp): W members of one system advanced together by the ordinary steppers.
// - RK4: every lane equals the scalar run of its member bit for bit (the lane kernel here is the
//   scalar right-hand side applied to each lane, so there is no vector-math rounding to allow for);
// - DOP853 with one shared step: every lane within the tolerance of the exact solution, with the
//   step count of the most demanding lane (the largest lane error norm chooses the step);
// - a lane whose f stops being finite is stopped alone; a stopped lane stays where it was;
// - an event hit records the run's work up to it (what a lane ended by it reports).
#include <catch2/catch.hpp>

#include "integrate/integrate.hpp"
#include "lanes.hpp"
#include "steppers/dop853.hpp"
#include "steppers/rk4.hpp"

#include <cmath>
#include <limits>
#include <vector>

using namespace rotgen;

namespace {

// The pendulum x'' = -w² sin x (state x, v), with w its parameter.
void pendulum(double w, const double* y, double* d) {
    d[0] = y[1];
    d[1] = -w * w * std::sin(y[0]);
}

// Its lanes: component c of lane l at y[c·W + l], each lane with its own w.
auto pendulum_lanes(const std::vector<double>& w) {
    const std::size_t lanes = w.size();
    const auto kernel = [w, lanes](double, const double* y, double* d) {
        for (std::size_t l = 0; l < lanes; ++l) {
            const double yl[2] = {y[l], y[lanes + l]};
            double dl[2];
            pendulum(w[l], yl, dl);
            d[l] = dl[0], d[lanes + l] = dl[1];
        }
    };
    return lane_system<double, decltype(kernel)>(kernel, 2, lanes);
}

struct scalar_pendulum {
    double w;
    std::size_t size() const { return 2; }
    void rhs(double, const double* y, double* d) const { pendulum(w, y, d); }
};

const std::vector<double> frequencies{0.5, 1.0, 1.7, 3.0};
const std::vector<double> amplitudes{0.1, 1.0, 2.0, 0.5};

Eigen::VectorXd lane_start() {
    const std::size_t w = frequencies.size();
    Eigen::VectorXd y = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(2 * w));
    for (std::size_t l = 0; l < w; ++l)
        y[static_cast<Eigen::Index>(l)] = amplitudes[l];
    return y;
}

std::vector<double> times(int n, double t_end) {
    std::vector<double> t;
    for (int i = 0; i <= n; ++i)
        t.push_back(t_end * i / n);
    return t;
}

} // namespace

TEST_CASE("rk4 lanes equal the scalar runs of their members bit for bit") {
    auto sys = pendulum_lanes(frequencies);
    const std::vector<double> t = times(37, 10.0); // samples inside steps: the Hermite interpolant
    std::vector<Eigen::VectorXd> lane_samples;
    Eigen::VectorXd y = lane_start();
    rk4<double> method;
    method.step = 0.013;
    const auto res = integrate(sys, method, 0.0, y, t, [&](double, const Eigen::VectorXd& v) {
        lane_samples.push_back(v);
    });
    REQUIRE(res.ok());
    const std::size_t w = frequencies.size();
    for (std::size_t l = 0; l < w; ++l) {
        Eigen::VectorXd ys(2);
        ys << amplitudes[l], 0.0;
        std::vector<Eigen::VectorXd> scalar_samples;
        const auto r =
            integrate(scalar_pendulum{frequencies[l]}, method, 0.0, ys, t,
                      [&](double, const Eigen::VectorXd& v) { scalar_samples.push_back(v); });
        REQUIRE(r.ok());
        REQUIRE(r.stats.accepted == res.stats.accepted);
        REQUIRE(r.stats.rhs_evals == res.stats.rhs_evals);
        REQUIRE(scalar_samples.size() == lane_samples.size());
        for (std::size_t k = 0; k < scalar_samples.size(); ++k)
            for (Eigen::Index c = 0; c < 2; ++c)
                REQUIRE(lane_samples[k][c * Eigen::Index(w) + Eigen::Index(l)] ==
                        scalar_samples[k][c]);
    }
}

// The linear oscillator x'' = -w² x per lane: exact x = a cos(w t).
TEST_CASE("dop853 lanes share one step chosen by the largest lane error") {
    const std::size_t w = frequencies.size();
    const auto kernel = [](double, const double* y, double* d) {
        for (std::size_t l = 0; l < frequencies.size(); ++l) {
            const std::size_t n = frequencies.size();
            d[l] = y[n + l], d[n + l] = -frequencies[l] * frequencies[l] * y[l];
        }
    };
    const lane_system<double, decltype(kernel)> sys(kernel, 2, w);
    dop853<double> method(1e-8, 1e-10);
    Eigen::VectorXd y = lane_start();
    const auto res = integrate(sys, method, 0.0, y, 20.0);
    REQUIRE(res.ok());
    std::size_t most = 0;
    for (std::size_t l = 0; l < w; ++l) {
        const double exact = amplitudes[l] * std::cos(frequencies[l] * 20.0);
        const double err = std::abs(y[Eigen::Index(l)] - exact);
        // observed 1.5e-16, 2.0e-12, 3.4e-10, 2.4e-9 (the fastest lane: 9.5 periods)
        CHECK(err < 1e-8);
        const auto lane =
            make_system<double, 2>([f = frequencies[l]](double, const double* v, double* d) {
                d[0] = v[1], d[1] = -f * f * v[0];
            });
        Eigen::Vector2d ys(amplitudes[l], 0.0);
        const auto r = integrate(lane, method, 0.0, ys, 20.0);
        most = std::max(most, r.stats.accepted);
    }
    // the most demanding lane chooses every step: observed 108 steps, as its own run takes
    CHECK(res.stats.accepted >= most);
    CHECK(res.stats.accepted <= most + 5);
}

TEST_CASE("a lane whose f is not finite stops alone, the others run on") {
    // lane 1: x' = x while x <= 1.5 (t < ln 1.5), f = NaN beyond; the other lanes x' = -x
    const auto kernel = [](double, const double* y, double* d) {
        for (std::size_t l = 0; l < 3; ++l)
            d[l] = l != 1 ? -y[l] : y[l] <= 1.5 ? y[l] : std::nan("");
    };
    lane_system<double, decltype(kernel)> sys(kernel, 1, 3);
    Eigen::VectorXd y = Eigen::VectorXd::Ones(3);
    dop853<double> method(1e-10, 1e-12);
    const auto res = integrate(sys, method, 0.0, y, 2.0);
    REQUIRE(res.ok());
    CHECK(sys.failed_lane(1));
    CHECK(!sys.failed_lane(0));
    CHECK(sys.is_live(0));
    CHECK(!sys.is_live(1));
    // observed 1.4e-12 for both
    CHECK(std::abs(y[0] - std::exp(-2.0)) < 1e-11);
    CHECK(std::abs(y[2] - std::exp(-2.0)) < 1e-11);

    // a stopped lane keeps its state
    lane_system<double, decltype(kernel)> again(kernel, 1, 3);
    again.stop(1);
    Eigen::VectorXd z = Eigen::VectorXd::Ones(3);
    rk4<double> fixed;
    fixed.step = 0.01;
    REQUIRE(integrate(again, fixed, 0.0, z, 2.0).ok());
    CHECK(z[1] == 1.0);
    CHECK(!again.failed_lane(1));
    CHECK(std::abs(z[0] - std::exp(-2.0)) < 1e-10); // RK4 at h = 0.01: observed 2.3e-11
}

TEST_CASE("the finiteness tests see an infinity or a NaN at every position") {
    // all_finite and lane_system::rhs sum x - x in four partial sums plus a remainder: every
    // position of every length must count
    for (std::size_t n = 1; n <= 13; ++n)
        for (std::size_t at = 0; at < n; ++at)
            for (double bad : {std::numeric_limits<double>::infinity(), -HUGE_VAL, std::nan("")}) {
                Eigen::VectorXd v = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(n), 1e308);
                CHECK(detail::all_finite(v));
                v[static_cast<Eigen::Index>(at)] = bad;
                CHECK(!detail::all_finite(v));
            }
    // 3 components of 4 lanes: f not finite at one position fails that lane alone
    for (std::size_t at = 0; at < 12; ++at) {
        const auto kernel = [at](double, const double*, double* d) {
            for (std::size_t i = 0; i < 12; ++i)
                d[i] = i == at ? std::numeric_limits<double>::infinity() : -1e300;
        };
        const lane_system<double, decltype(kernel)> sys(kernel, 3, 4);
        std::vector<double> y(12, 0.0), d(12);
        sys.rhs(0, y.data(), d.data());
        for (std::size_t l = 0; l < 4; ++l) {
            CHECK(sys.failed_lane(l) == (l == at % 4));
            for (std::size_t c = 0; c < 3; ++c) // a failed lane's derivatives are 0
                CHECK(d[c * 4 + l] == (l == at % 4 ? 0.0 : -1e300));
        }
    }
}

TEST_CASE("an event hit records the work up to it: a run it stops reports the same") {
    // x' = v, v' = -x from (1, 0): x falls through 0 at t = pi/2 (terminal) and a non-terminal
    // watch on v rising through 0 at t = pi, past the terminal one in the second run only
    const auto sys = make_system<double, 2>(
        [](double, const double* y, double* d) { d[0] = y[1], d[1] = -y[0]; });
    for (const bool stop : {true, false}) {
        event_set<double, Eigen::Vector2d> events;
        events.add([](double, const Eigen::Vector2d& y) { return y[0]; }, event_direction::falling,
                   stop, "x");
        Eigen::Vector2d y(1.0, 0.0);
        const std::vector<double> t = times(10, 4.0);
        rk4<double> method;
        method.step = 0.01;
        const auto res = integrate(
            sys, method, 0.0, y, t, [](double, const Eigen::Vector2d&) {}, events);
        REQUIRE(events.hits().size() == 1);
        const step_stats& work = events.hits()[0].work;
        // the step that holds pi/2: the 158th (observed 158 steps, 633 evaluations with the
        // evaluation at its end for the event search)
        CHECK(work.steps == 158);
        CHECK(work.rhs_evals >= 4 * work.steps);
        if (stop) {
            CHECK(res.code == status::stopped_by_event);
            CHECK(res.stats.steps == work.steps);
            CHECK(res.stats.rhs_evals == work.rhs_evals);
        } else {
            CHECK(res.ok());
            CHECK(res.stats.steps == 400);
        }
    }
}
