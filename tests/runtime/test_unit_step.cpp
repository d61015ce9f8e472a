// The error per unit step (step_control.hpp, error_layout::span): calibrate() refuses a layout
// without the run's span, and the floor the adaptive loop puts under a step's share where the
// estimate shows rounding (share_floor) is raised by a rejected attempt whose estimate did not
// fall with the step, and by a run of rejections, and by nothing else.
#include <catch2/catch.hpp>

#include "rotgen.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

using namespace rotgen;

TEST_CASE("calibrate refuses a layout without the run's span", "[step_control]") {
    constexpr signed char q = error_layout::attitude;
    dop853<double> method(1e-8, 1e-8);
    CHECK_THROWS_AS(calibrate(method, error_layout{{q, q, q, q, 0, 0, 0}, {}}),
                    std::invalid_argument);
    calibrate(method, error_layout{{q, q, q, q, 0, 0, 0}, {}, 10});
    CHECK(method.layout.span == 10);
    CHECK(detail::unit_step_factor(method.layout, 0.5) == 20); // span / |h|
}

TEST_CASE("the share's floor rises where the estimate does not fall with the step",
          "[step_control]") {
    error_layout layout;
    layout.span = 2;
    SECTION("an estimate that falls as truncation does leaves the share alone") {
        detail::share_floor<double> floor(layout);
        floor.attempted(1e-3, 100, true);
        floor.attempted(5e-4, 100.0 / 128, true); // err ∝ h^7 (DOP853 per unit step)
        CHECK(floor.held(1e-5, 3.0) == 3.0);
    }
    SECTION("an estimate that stays while the step halves sets the floor at the first step") {
        detail::share_floor<double> floor(layout);
        floor.attempted(1e-3, 100, true);
        floor.attempted(5e-4, 90, true);
        // the floor is the share of the first attempt, 1e-3 / 2: a step of 1e-5 is held to it
        CHECK(floor.held(1e-5, 100) == Approx(100 * 1e-5 / 1e-3));
        CHECK(floor.held(2e-3, 100) == 100); // a step longer than the floor keeps its own share
    }
    SECTION("a third of the attempts rejected raises the floor, and it doubles while they last") {
        detail::share_floor<double> floor(layout);
        for (int i = 0; i < 120; ++i) // every other attempt rejected, each at h = 1e-4
            floor.attempted(1e-4, i % 2 ? 2.0 : 0.5, i % 2 == 1);
        const double once = floor.held(1e-6, 1.0);
        CHECK(once < 1.0);
        for (int i = 0; i < 50; ++i)
            floor.attempted(1e-4, i % 2 ? 2.0 : 0.5, i % 2 == 1);
        CHECK(floor.held(1e-6, 1.0) == Approx(once / 2));
    }
    SECTION("without a span there is no floor") {
        detail::share_floor<double> floor(error_layout{});
        for (int i = 0; i < 200; ++i)
            floor.attempted(1e-4 / (i + 1), 100, true);
        CHECK(floor.held(1e-9, 100) == 100);
    }
}

// The adaptive loop takes each step as (t + h) − t, the step its clock takes (adaptive.hpp): a
// state advanced by h while t advanced by the rounded t + h drifts from its time, by the sum of
// the roundings over hundreds of thousands of steps, and at 1000 rad/s that drift is a phase error.
TEST_CASE("a run of many steps through fast motion keeps to its own time", "[step_control]") {
    constexpr double omega = 1000; // y = (cos ωt, −sin ωt)
    const auto sys = make_system<double, 2>([](double, const double* y, double* d) {
        d[0] = omega * y[1];
        d[1] = -omega * y[0];
    });
    std::vector<double> times;
    for (int k = 0; k <= 200; ++k)
        times.push_back(0.05 * k);
    for (const bool dop : {false, true}) {
        double worst = 0;
        const auto watch = [&](double t, const auto& y) {
            worst = std::max({worst, std::abs(y[0] - std::cos(omega * t)),
                              std::abs(y[1] + std::sin(omega * t))});
        };
        Eigen::Vector2d y(1.0, 0.0);
        error_layout layout{{0, 0}, {}, 10}; // one rate group, over t = 0..10
        integration_result<double> r;
        if (dop) {
            dop853<double> m(1e-10, 1e-10);
            m.max_steps = 10000000;
            calibrate(m, layout);
            r = integrate(sys, m, 0.0, y, times, watch);
        } else {
            dopri5<double> m(1e-10, 1e-10);
            m.max_steps = 10000000;
            calibrate(m, layout);
            r = integrate(sys, m, 0.0, y, times, watch);
        }
        INFO(status_name(r.code) << ": " << r.message);
        REQUIRE(r.ok());
        INFO((dop ? "dop853" : "dopri5") << ": " << r.stats.steps << " steps, error " << worst);
        CHECK(r.stats.steps > 50000); // many steps: the drift is their roundings' sum
        // observed: dopri5 1.1e-11 in 1,893,501 steps, dop853 7.9e-12 in 96,884 (with t + h added
        // as it rounds, the state advanced by h: 6.1e-10 and 1.6e-10)
        CHECK(worst < 5e-11);
    }
}
