// run/chart_kinematics.cpp's sin_theta_below, the chart check a run makes at every sample: it
// answers without a sine where the middle angle is plainly far from the singular set, and must
// give sin_theta_of(s, form, y) < bound's answer everywhere, for proper and Tait-Bryan sequences,
// near the bound and far from it.
#include "expr/angles.hpp"
#include "run/angle_chart.hpp"
#include "run/chart_kinematics.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

using namespace rotgen;

namespace {

// The middle angles to try: random ones over many turns, and ones within 1e-9 of where the
// chart distance crosses each bound (asin(bound) and its images under beta -> pi - beta, + k pi).
std::vector<double> angles(bool proper, const std::vector<double>& bounds) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-40, 40), tiny(-1e-9, 1e-9);
    std::vector<double> a;
    for (int i = 0; i < 20000; ++i)
        a.push_back(u(rng));
    const double pi = 3.14159265358979323846, shift = proper ? 0 : pi / 2;
    for (double b : bounds)
        for (int k = -3; k <= 3; ++k)
            for (double base : {std::asin(b), pi - std::asin(b)})
                for (int j = 0; j < 50; ++j)
                    a.push_back(base + k * pi + shift + tiny(rng));
    return a;
}

} // namespace

TEST_CASE("the chart check at a sample gives the sine's answer", "[run]") {
    const bool proper = GENERATE(true, false);
    angle_convention c;
    if (!proper) c.axes = {2, 1, 0}; // z-y-x: |cos pitch|
    const euler_sequence s = sequence_of(c);
    const std::vector<double> bounds{0.1, 0.3, 0.9};
    const form_kind form = GENERATE(form_kind::lagrangian, form_kind::hamiltonian);
    CAPTURE(proper, to_string(form));
    Eigen::VectorXd y = Eigen::VectorXd::Zero(6);
    int differ = 0, near = 0;
    for (double beta : angles(proper, bounds))
        for (double b : bounds) {
            y[1] = beta;
            const double d = sin_theta_of(s, form, y);
            near += std::abs(d - b) < 1e-8;
            differ += sin_theta_below(s, form, y, b) != (d < b);
        }
    CHECK(near > 1000); // the angles do test the bound's neighbourhood (observed 2,100)
    CHECK(differ == 0);
}
