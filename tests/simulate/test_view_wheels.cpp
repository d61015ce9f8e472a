// The view (`simulate --view`, view/) of a body with wheels: the angular momentum it draws is the
// body's and the wheels' together, L = R(q) (I omega + sum h_i a_i), which is constant in space
// when no external torque acts; R(q) I omega alone, which the view computes for a body without
// wheels when the run did not record Lx..Lz, leaves the wheels out.
#include "support.hpp"

#include "run/engine.hpp"
#include "run/prepared.hpp"
#include "scene/scene.hpp"
#include "support/timings.hpp"
#include "view/view.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

TEST_CASE("the view of a body with wheels draws L with the wheels' momenta", "[view][wheels]") {
    // the shipped slew: at rest, wheels at rest, so L = 0 throughout while the motors turn the
    // body (and the wheels take up the opposite momentum)
    rotgen::scene_spec s = rotgen::load_scene(std::string(ROTGEN_SOURCE_DIR) +
                                              "/models/scenes/reaction_wheel_slew.yaml");
    s.t_end = 10, s.samples = 201;
    s.record = {"q0", "q1", "q2", "q3", "omega1", "omega2", "omega3"}; // no Lx..Lz
    const rotgen::scene_spec viewed = rotgen::scene_for_view(s, "--view");
    rotgen::stage_timings timings;
    const rotgen::prepared_scene prepared(viewed, timings);
    const rotgen::run_result r = rotgen::run_member(prepared, rotgen::values_of(viewed), timings);
    REQUIRE(r.ok);
    const rotgen::view_data d = rotgen::view_of_run(viewed, r);
    REQUIRE(d.L.size() == 3 * r.rows.size());
    double largest_L = 0;
    for (double l : d.L)
        largest_L = std::max(largest_L, std::abs(l));
    INFO("largest L " << largest_L);
    CHECK(largest_L < 3e-15); // observed 3.1e-16: rounding of |L| = 0
    // the body alone carries momentum meanwhile (|omega| up to 0.27, I omega of the same order)
    const auto w1 = std::find(r.columns.begin(), r.columns.end(), "omega1") - r.columns.begin();
    double largest_w = 0;
    for (const auto& row : r.rows)
        largest_w = std::max(largest_w, std::hypot(row[w1 + 1], row[w1 + 2], row[w1 + 3]));
    CHECK(largest_w > 0.03); // observed 0.27
    // from rows without Lx..Lz (a CSV given to `rotgen view`) a wheel model's L is not drawn
    const rotgen::run_result only = rotgen::only_scene_records(r, s);
    const rotgen::view_data from_csv = rotgen::view_of_rows(s, only.columns, only.rows, s.where);
    CHECK(from_csv.L.empty());
}
