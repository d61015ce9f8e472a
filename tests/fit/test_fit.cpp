// rotgen fit against a known truth: synthetic gyro and star-tracker data of rotgen's own runs,
// with seeded noise (fit_support.hpp).
#include "fit_support.hpp"

#include <catch2/catch.hpp>

using namespace rotgen;
using namespace rotgen::test;
using Catch::Matchers::Contains;

namespace {

const std::string top_scene = std::string(ROTGEN_SOURCE_DIR) + "/tests/fit/top_fit.yaml";
const std::string free_scene = std::string(ROTGEN_SOURCE_DIR) + "/tests/fit/free_body_fit.yaml";
const std::vector<std::string> inertia{"Ixx", "Iyy", "Izz", "Ixy", "Ixz", "Iyz"};

std::vector<std::string> keys_of(const std::vector<std::string>& names) {
    std::vector<std::string> keys;
    for (const auto& n : names)
        keys.push_back("parameters." + n);
    return keys;
}

// The top's scene with its six inertia entries 20-30% away from the truth (still physical).
scene_spec top_start(const scene_spec& truth) {
    scene_spec start = truth;
    const double factor[] = {1.25, 0.78, 1.22, 1.3, 0.72, 1.28};
    for (std::size_t i = 0; i < inertia.size(); ++i)
        set_parameter(start, inertia[i], parameter_of(truth, inertia[i]) * factor[i]);
    return start;
}

} // namespace

TEST_CASE("fit recovers the full-tensor top's six inertia entries within 3 standard errors",
          "[fit]") {
    const scene_spec truth = load_scene(top_scene);
    const synthetic d = measure(truth, 7, 200, 1e-3, 1e-4);
    const fit_result r = fit_synthetic(top_start(truth), d, keys_of(inertia),
                                       "omega1=1e-3,omega2=1e-3,omega3=1e-3,q=1e-4");
    REQUIRE(r.converged);
    for (std::size_t i = 0; i < inertia.size(); ++i) {
        const auto k = static_cast<Eigen::Index>(i);
        INFO(inertia[i] << " = " << r.values[k] << " +- " << r.stderrs[k] << ", truth "
                        << parameter_of(truth, inertia[i]));
        CHECK(std::abs(r.values[k] - parameter_of(truth, inertia[i])) < 3 * r.stderrs[k]);
        CHECK(r.stderrs[k] < 1e-2); // observed ~1e-4: the data do determine them
    }
    // chi2 of a right model with right sigmas: about its dof (1400 values - 6)
    CHECK(r.dof == 200 * 6 - 6);
    CHECK(r.chi2 / double(r.dof) > 0.8);
    CHECK(r.chi2 / double(r.dof) < 1.2);
}

// In the lagrangian form the run gives d(q0..q3)/d(key) as well (the attitude from the angles):
// the fit's Jacobian is the sensitivities, one run per Jacobian where central differences take
// 2k more, and the estimates are the body form's.
TEST_CASE("fit in the lagrangian form takes its Jacobian from the sensitivities and agrees with "
          "the body form",
          "[fit]") {
    // the top tilted further than top_fit.yaml's, so that theta stays far from 0 at every iterate
    // (a run near it would switch chart, which sensitivities do not cross)
    const test::scratch_file f("fit_tilted_top.yaml",
                               "model: " + test::model_path("full_tensor_top") + R"(
form: body
initial: {phi: 0.2, theta: 1.1, psi: 0.1, omega1: 1.0, omega2: -0.5, omega3: 8.0}
time: {start: 0, end: 1.5, samples: 101}
integrator: {method: dop853, rtol: 1e-11, atol: 1e-12}
record: [omega1, omega2, omega3]
)");
    const scene_spec truth = load_scene(f.path);
    const synthetic d = measure(truth, 7, 200, 1e-3, 1e-4);
    const std::string sigma = "omega1=1e-3,omega2=1e-3,omega3=1e-3,q=1e-4";
    const fit_result body = fit_synthetic(top_start(truth), d, keys_of(inertia), sigma);
    scene_spec start = top_start(truth);
    start.form = form_kind::lagrangian;
    const fit_result r = fit_synthetic(start, d, keys_of(inertia), sigma);
    REQUIRE(body.converged);
    REQUIRE(r.converged);
    INFO(r.evaluations << " evaluations, " << r.jacobians << " Jacobians, " << r.runs << " runs");
    CHECK(r.sensitivities);
    // one run per evaluation, and one more where a Jacobian is asked at a point not evaluated
    // (observed 12 runs for 10 evaluations and 7 Jacobians; differences would add 12 per Jacobian)
    CHECK(r.runs <= static_cast<std::size_t>(r.evaluations + r.jacobians));
    for (std::size_t i = 0; i < inertia.size(); ++i) {
        const auto k = static_cast<Eigen::Index>(i);
        INFO(inertia[i] << ": lagrangian " << r.values[k] << ", body " << body.values[k] << " +- "
                        << body.stderrs[k]);
        // the same model integrated in two forms: the same fit to the runs' accuracy
        CHECK(std::abs(r.values[k] - body.values[k]) < 2e-7 * body.stderrs[k]); // observed 2.1e-8
        CHECK_THAT(r.stderrs[k], Catch::Matchers::WithinRel(body.stderrs[k], 2e-9)); // obs. 1.5e-10
    }
    CHECK_THAT(r.chi2, Catch::Matchers::WithinRel(body.chi2, 5e-10)); // observed 5.0e-11
}

// top_fit.yaml's top, less tilted: at some iterate its Euler-angle run comes near theta = 0 and
// switches to the body form, which sensitivities do not cross; the fit goes on by differences.
TEST_CASE("fit in the lagrangian form whose run switches chart takes differences and converges",
          "[fit]") {
    const scene_spec truth = load_scene(top_scene);
    const synthetic d = measure(truth, 7, 200, 1e-3, 1e-4);
    scene_spec start = top_start(truth);
    start.form = form_kind::lagrangian;
    const fit_result r =
        fit_synthetic(start, d, keys_of(inertia), "omega1=1e-3,omega2=1e-3,omega3=1e-3,q=1e-4");
    REQUIRE(r.converged);
    INFO(r.evaluations << " evaluations, " << r.jacobians << " Jacobians, " << r.runs << " runs");
    CHECK_FALSE(r.sensitivities);
    // observed 131 runs for 12 evaluations and 9 Jacobians (the first from the sensitivities)
    CHECK(r.runs >= static_cast<std::size_t>(r.evaluations + 12 * (r.jacobians - 1)));
    for (std::size_t i = 0; i < inertia.size(); ++i) {
        const auto k = static_cast<Eigen::Index>(i);
        CHECK(std::abs(r.values[k] - parameter_of(truth, inertia[i])) < 3 * r.stderrs[k]);
    }
}

TEST_CASE("fit refuses the top's inertia and centre of mass free together as not identifiable",
          "[fit]") {
    const scene_spec truth = load_scene(top_scene);
    const synthetic d = measure(truth, 7, 200, 1e-3, 1e-4);
    std::vector<std::string> free = keys_of(inertia);
    for (const char* c : {"parameters.cx", "parameters.cy", "parameters.cz"})
        free.push_back(c);
    REQUIRE_THROWS_WITH(
        fit_synthetic(top_start(truth), d, free, "omega1=1e-3,omega2=1e-3,omega3=1e-3,q=1e-4"),
        Contains("the data do not determine") && Contains("parameters.cz") &&
            Contains("common scale") && Contains("--free"));
}

TEST_CASE("fit reports the free body's scale ambiguity and fixing I3 recovers I1/I3 and I2/I3",
          "[fit]") {
    const scene_spec truth = load_scene(free_scene);
    const synthetic d = measure(truth, 11, 200, 1e-3, 0);
    scene_spec start = truth;
    set_parameter(start, "I1", 1.25), set_parameter(start, "I2", 2.4),
        set_parameter(start, "I3", 3.0);
    const std::string sigma = "omega1=1e-3,omega2=1e-3,omega3=1e-3";
    REQUIRE_THROWS_WITH(
        fit_synthetic(start, d, {"parameters.I1", "parameters.I2", "parameters.I3"}, sigma),
        Contains("parameters.I1, parameters.I2, parameters.I3 together") &&
            Contains("common scale"));
    // I3 fixed at 1.5 times the truth (2.5): the ratios are what is fitted, from 20-25% away
    set_parameter(start, "I3", 3.75), set_parameter(start, "I1", 1.875),
        set_parameter(start, "I2", 2.4);
    const fit_result r = fit_synthetic(start, d, {"parameters.I1", "parameters.I2"}, sigma);
    REQUIRE(r.converged);
    const double ratio1 = r.values[0] / 3.75, ratio2 = r.values[1] / 3.75;
    INFO("I1/I3 " << ratio1 << " +- " << r.stderrs[0] / 3.75 << ", I2/I3 " << ratio2 << " +- "
                  << r.stderrs[1] / 3.75);
    CHECK(std::abs(ratio1 - 1.0 / 2.5) < 3 * r.stderrs[0] / 3.75);
    CHECK(std::abs(ratio2 - 2.0 / 2.5) < 3 * r.stderrs[1] / 3.75);
}

TEST_CASE("fit without sigmas weights each column by its residual RMS and scales the covariance",
          "[fit]") {
    const scene_spec truth = load_scene(free_scene);
    const synthetic d = measure(truth, 5, 200, 2e-3, 0);
    scene_spec start = truth;
    set_parameter(start, "I1", 1.25);
    const fit_result r = fit_synthetic(start, d, {"parameters.I1", "parameters.I2"}, "");
    REQUIRE(r.converged);
    CHECK_FALSE(r.sigma_given);
    for (std::size_t c = 0; c < r.columns.size(); ++c)
        CHECK_THAT(r.sigma[c], Catch::Matchers::WithinRel(2e-3, 0.15)); // observed within 8%
    CHECK_THAT(r.variance_scale, Catch::Matchers::WithinRel(1.0, 0.05));
    CHECK(std::abs(r.values[0] - 1.0) < 3 * r.stderrs[0]);
}

// The standard errors mean what they say: over 40 seeds (a longer test: ~40 fits), the 2-sigma
// intervals hold the truth about 95% of the time and ((estimate - truth) / sigma)^2 averages 1.
TEST_CASE("fit standard errors are calibrated over 40 seeds", "[fit][long]") {
    const scene_spec truth = load_scene(top_scene);
    const std::vector<std::string> checked{"Ixx", "Izz", "Ixy"};
    std::vector<int> inside(checked.size(), 0);
    std::vector<double> z2(checked.size(), 0);
    const int seeds = 40;
    for (int seed = 100; seed < 100 + seeds; ++seed) {
        const synthetic d = measure(truth, static_cast<std::uint64_t>(seed), 200, 1e-3, 1e-4);
        const fit_result r = fit_synthetic(top_start(truth), d, keys_of(inertia),
                                           "omega1=1e-3,omega2=1e-3,omega3=1e-3,q=1e-4");
        INFO("seed " << seed << ": " << r.stop << " after " << r.evaluations << " evaluations, "
                     << r.iterations << " iterations, chi2 " << r.chi2 << " values "
                     << r.values.transpose());
        REQUIRE(r.converged);
        for (std::size_t c = 0; c < checked.size(); ++c) {
            const auto k = static_cast<Eigen::Index>(
                std::find(inertia.begin(), inertia.end(), checked[c]) - inertia.begin());
            const double z = (r.values[k] - parameter_of(truth, checked[c])) / r.stderrs[k];
            inside[c] += std::abs(z) < 2;
            z2[c] += z * z / seeds;
        }
    }
    for (std::size_t c = 0; c < checked.size(); ++c) {
        INFO(checked[c] << ": coverage " << inside[c] / double(seeds) << ", mean z^2 " << z2[c]);
        CHECK(inside[c] / double(seeds) >= 0.85);
        CHECK(z2[c] >= 0.5);
        CHECK(z2[c] <= 2.0);
    }
}
