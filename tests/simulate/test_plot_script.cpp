// The plot of a run: conserved quantities are drawn as their drift from the start (their raw
// values fill an axis with ticks that all read the same: "15 15 15"), and every panel has the same
// margins, so that the time axes line up.
#include "simulate/plot.hpp"

#include <catch2/catch.hpp>

using Catch::Matchers::Contains;

TEST_CASE("simulate plot: conserved momenta and the energy are drawn as drifts", "[simulate]") {
    const std::string script = rotgen::plot_script(
        "out.png", "out.png", "run.csv", {"theta", "p_phi", "p_theta", "energy"}, "heavy_top",
        {{"p_phi", 13.163738428355591}, {"energy", 225.5}});
    // p_phi is conserved: its drift, in a panel of drifts, labelled as such
    CHECK_THAT(script, Contains("'run.csv' using 1:($3 - (13.163738428355591)) with lines title "
                                "'p_phi - p_phi(0)'"));
    CHECK_THAT(script, Contains("set ylabel 'conserved momenta - value at t0'"));
    CHECK_THAT(script, Contains("using 1:($5 - (225.5)) with lines title 'energy - energy(0)'"));
    // p_theta is not conserved: its value, in the momenta panel
    CHECK_THAT(script, Contains("'run.csv' using 1:4 with lines title 'p_theta'"));
    CHECK_THAT(script, Contains("set ylabel 'momenta'"));
    CHECK(script.find("using 1:3 with") == std::string::npos); // never p_phi's raw value
}

TEST_CASE("simulate plot: every panel has the same margins", "[simulate]") {
    const std::string script =
        rotgen::plot_script("o.png", "o.png", "r.csv", {"theta", "omega1", "energy"}, "m", {});
    const auto lm = script.find("set lmargin at screen 0.11");
    const auto rm = script.find("set rmargin at screen 0.76");
    const auto multiplot = script.find("set multiplot");
    REQUIRE(lm != std::string::npos);
    REQUIRE(rm != std::string::npos);
    CHECK(lm < multiplot); // set once, before the panels: all of them share it
    CHECK(rm < multiplot);
    CHECK(script.find("set lmargin", lm + 1) == std::string::npos);
}
