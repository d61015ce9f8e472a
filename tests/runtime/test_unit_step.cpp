// The error per unit step (step_control.hpp, error_layout::span): calibrate() refuses a layout
// without the run's span, and the floor the adaptive loop puts under a step's share where the
// estimate shows rounding (share_floor) is raised by a rejected attempt whose estimate did not
// fall with the step, and by a run of rejections, and by nothing else.
#include <catch2/catch.hpp>

#include "rotgen.hpp"

#include <stdexcept>

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
