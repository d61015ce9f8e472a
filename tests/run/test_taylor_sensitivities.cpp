// The Taylor method with sensitivities (run/taylor_sensitivity.hpp: the recurrences of the
// augmented system (y, S)) against DOP853's variational equations on the same scenes, in every
// form (the reduced form's cyclic momenta are dP/ds inputs of the kernel), with events, and with
// `error_control: false`.
#include "support.hpp"

#include "run/engine.hpp"
#include "run/prepared.hpp"
#include "run/taylor_sensitivity.hpp"
#include "scene/scene.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

using namespace rotgen;

namespace {

scene_spec scene_of(const std::string& name, const std::string& text) {
    const test::scratch_file f("taylor_sens_" + name + ".yaml", text);
    return load_scene(f.path);
}

rotgen::run_result run_scene(const scene_spec& scene) {
    stage_timings timings;
    const prepared_scene prepared(scene, timings);
    return run_member(prepared, values_of(scene), timings);
}

scene_spec with_method(scene_spec s, const std::string& method) {
    s.integrator.method = method;
    return s;
}

// The largest difference of two runs' d(...) columns (and d(t_event)/d(key) rows), relative to
// max(|d|, 1e-3).
double worst_difference(const rotgen::run_result& a, const rotgen::run_result& b) {
    REQUIRE(a.sensitivity_columns == b.sensitivity_columns);
    REQUIRE(a.sensitivity_rows.size() == b.sensitivity_rows.size());
    REQUIRE(a.event_sensitivity_rows.size() == b.event_sensitivity_rows.size());
    double worst = 0;
    const auto compare = [&](const std::vector<double>& x, const std::vector<double>& y) {
        REQUIRE(x.size() == y.size());
        for (std::size_t c = 0; c < x.size(); ++c)
            worst = std::max(worst, std::abs(x[c] - y[c]) / std::max(std::abs(y[c]), 1e-3));
    };
    for (std::size_t s = 0; s < a.sensitivity_rows.size(); ++s)
        compare(a.sensitivity_rows[s], b.sensitivity_rows[s]);
    for (std::size_t e = 0; e < a.event_sensitivity_rows.size(); ++e)
        compare(a.event_sensitivity_rows[e], b.event_sensitivity_rows[e]);
    return worst;
}

const std::string heavy_top = "model: " + test::model_path("heavy_top") + R"(
initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0.3, theta_dot: 0.1, psi_dot: 5}
time: {start: 0, end: 5, samples: 11}
integrator: {method: taylor, rtol: 1e-12, atol: 1e-14}
switch_chart: false
events: [{name: turn, when: theta_dot}]
)";

} // namespace

TEST_CASE("the Taylor method's sensitivities of the heavy top agree with DOP853's in every form",
          "[sensitivities][taylor]") {
    const auto [form, record, keys, bound] =
        GENERATE(table<std::string, std::string, std::string, double>(
            {{"lagrangian", "[theta, phi, theta_dot, psi_dot, energy, p_psi]",
              "[initial.theta, initial.psi_dot, parameters.h, parameters.I3]", 3e-11}, // 3.1e-12
             {"hamiltonian", "[theta, phi, p_theta, energy]",
              "[initial.theta, initial.phi_dot, parameters.M, parameters.I1]", 5e-11}, // 5.6e-12
             // the cyclic momenta are parameters there, moved by the initial rates and the inertia
             {"reduced", "[theta, theta_dot, energy]",
              "[initial.psi_dot, initial.phi_dot, parameters.I3, parameters.g]", 2e-11}, // 1.6e-12
             {"body", "[omega1, omega2, theta, energy, Lz]",
              "[initial.theta, initial.psi_dot, parameters.h, parameters.I1]", 5e-10}})); // 5.1e-11
    INFO(form);
    const scene_spec scene = scene_of(form, heavy_top + "form: " + form + "\nrecord: " + record +
                                                "\nsensitivities: " + keys + "\n");
    const rotgen::run_result taylor = run_scene(scene),
                             dop853 = run_scene(with_method(scene, "dop853"));
    REQUIRE(taylor.ok);
    REQUIRE(dop853.ok);
    // 4 keys for each recorded column (the body form's theta too, through the angles' recovery)
    REQUIRE(taylor.sensitivity_columns.size() == 4 * taylor.columns.size());
    REQUIRE(taylor.event_rows.size() >= 3);
    const double worst = worst_difference(taylor, dop853);
    CHECK(worst < bound); // observed: beside the bound
    // not vanishingly small: the sensitivities move
    double largest = 0;
    for (const auto& row : taylor.sensitivity_rows)
        for (const double d : row)
            largest = std::max(largest, std::abs(d));
    CHECK(largest > 1);
}

TEST_CASE("the Taylor method's sensitivities without error control keep the state's steps",
          "[sensitivities][taylor]") {
    const scene_spec with =
        scene_of("errcon", heavy_top + "form: lagrangian\nrecord: [theta]\nsensitivities: {keys: "
                                       "[initial.theta, parameters.h], error_control: false}\n");
    scene_spec plain = with, controlled = with;
    plain.sensitivities = {};
    controlled.sensitivities.error_control = true;
    const rotgen::run_result a = run_scene(with), b = run_scene(plain), c = run_scene(controlled);
    REQUIRE(a.ok);
    CHECK(a.stats.accepted == b.stats.accepted); // S is not in the step's norm
    CHECK(c.stats.accepted > b.stats.accepted);
    // two runs, each within its tolerance of the true motion: observed 1.5e-10 since the error per
    // unit step (4.0e-13 before, when the Taylor method's error was a hundredth of rtol)
    CHECK(worst_difference(a, c) < 1.5e-9);
}
