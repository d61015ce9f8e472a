// A member's initial kinematics in quad precision (generator/run/quad_start.hpp) against GiNaC's
// evaluation at 30 digits (initial_kinematics_of), which it replaces in every run: the same long
// doubles, for every way a scene gives its rates, with values written as expressions.
#ifdef ROTGEN_HAVE_QUADMATH

#include "support.hpp"

#include "expr/numbers.hpp"
#include "run/quad_start.hpp"
#include "scene/scene.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace rotgen;
using namespace rotgen::test;

namespace {

scene_spec scene_of(const std::string& model, const std::string& initial) {
    const scratch_file f("quad_start_" + model + "_" + std::to_string(initial.size()) + ".yaml",
                         "model: " + model_path(model) + "\ninitial: {" + initial +
                             "}\ntime: {end: 1, samples: 2}\n");
    return load_scene(f.path);
}

// How two starts' long doubles differ: relative differences, and differences below 1e-38, the
// rounding residue of a value that is exactly 0 (GiNaC's 30-digit floats leave ~1e-40 there in
// some of its term orders, which change from run to run; lowered programs cancel it exactly).
struct difference {
    long double largest = 0, largest_residue = 0;
    int differing = 0;
    void add(long double a, long double b) {
        if (a == b) return;
        if (std::abs(a - b) <= 1e-38L) {
            largest_residue = std::max(largest_residue, std::abs(a - b));
            return;
        }
        ++differing;
        largest = std::max(largest, std::abs(a - b) / std::abs(b));
    }
    void add(const initial_kinematics& a, const initial_kinematics& b) {
        CHECK(a.have_rates == b.have_rates);
        for (std::size_t i = 0; i < 3; ++i) {
            add(a.q[i], b.q[i]);
            add(a.qd[i], b.qd[i]);
            add(a.p[i], b.p[i]);
            add(a.omega[i], b.omega[i]);
        }
    }
};

// `members` random members of `scene` (angles, rates and parameters within their ranges, theta
// away from the poles) and the member with the scene's own values, both ways.
difference compare(scene_spec scene, int members) {
    const derivation d = derive(scene.model);
    const quad_start quad(scene, d);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> angle(-3, 3), polar(0.05, 3.09), rate(-20, 20),
        scale(0.5, 2);
    const scene_spec base = scene;
    difference diff;
    for (int m = 0; m <= members; ++m) {
        if (m > 0) {
            scene.angles = {angle(rng), polar(rng), angle(rng)};
            scene.initial_rates = {rate(rng), rate(rng), rate(rng)};
            for (std::size_t j = 0; j < scene.parameters.size(); ++j)
                scene.parameters[j] = base.parameters[j] * scale(rng);
        }
        const start_values v{scene.angles, scene.initial_rates, scene.parameters};
        const quad_start::programs* p = quad.programs_for(v);
        REQUIRE(p != nullptr);
        diff.add(quad.kinematics(*p, v), initial_kinematics_of(scene, d));
    }
    return diff;
}

} // namespace

TEST_CASE("the quad start gives GiNaC's long doubles whether rates or momenta or omega start it",
          "[run][quad]") {
    using row = std::tuple<std::string, std::string>;
    const auto [model, initial] = GENERATE(table<std::string, std::string>({
        row{"heavy_top", "phi: 0.1, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30"},
        row{"full_tensor_top", "phi: 0.3, theta: 0.7, psi: 1.1, p_phi: 0.5, p_theta: -0.2, "
                               "p_psi: 3"},
        row{"cube_on_corner", "phi: 0.3, theta: 1.2, psi: 1.1, omega1: 0.5, omega2: -0.2, "
                              "omega3: 4"},
        row{"damped_driven_top", "phi: 1, theta: 2, psi: -1, omega1: 0.5, omega2: 7, omega3: 0"},
        row{"free_asymmetric_top", "phi: 0.2, theta: 1, psi: 2, phi_dot: 1, theta_dot: -1, "
                                   "psi_dot: 5"},
        row{"heavy_top", "phi: 0, theta: 0.5, psi: 0, p_phi: 0.3, p_theta: 0, p_psi: 15"},
        row{"full_tensor_top", "phi: 0.3, theta: 0.7, psi: 1.1, omega1: 1, omega2: 2, omega3: 3"},
        row{"cube_on_corner", "phi: 0, theta: 0.9, psi: 0.785, phi_dot: 0, theta_dot: 0.1, "
                              "psi_dot: 2"},
    }));
    INFO(model << ": " << initial);
    // 401 members x 12 values per model and start: observed no relative difference at all (the two
    // agree unless a value lies within ~1e-30 of a long-double rounding boundary: one would be 1
    // ulp, 1.1e-19), and a residue of 3.7e-40 against an exact 0 in some runs.
    const difference d = compare(scene_of(model, initial), 400);
    CHECK(d.differing <= 1);
    CHECK(d.largest <= 1.1e-19L);
    CHECK(d.largest_residue <= 4e-39L);
}

TEST_CASE("the quad start substitutes values written as expressions exactly", "[run][quad]") {
    // theta = pi/2: p_psi = I3 (phi_dot cos theta + psi_dot) = 0 exactly, as GiNaC gives it; a
    // quad cos(pi/2) would leave 6e-35 I3 there. pi/3 and 2*pi*I3 are not decimals either.
    const scene_spec scene =
        scene_of("heavy_top", "phi: pi/3, theta: pi/2, psi: 0, phi_dot: 2*pi*I3, "
                              "theta_dot: 1/3, psi_dot: 0");
    const derivation d = derive(scene.model);
    const quad_start quad(scene, d);
    const start_values v{scene.angles, scene.initial_rates, scene.parameters};
    const quad_start::programs* p = quad.programs_for(v);
    REQUIRE(p != nullptr);
    const initial_kinematics k = quad.kinematics(*p, v);
    CHECK(k.p[2] == 0);
    CHECK(k.omega[2] == 0); // omega3 = phi_dot cos theta + psi_dot
    difference diff;
    diff.add(k, initial_kinematics_of(scene, d));
    CHECK(diff.differing == 0);
    // Theta one double below pi/2 is a decimal: another program, with cos theta = 2.8e-16. The
    // decimal rounded to quad's 113 bits is off by up to 1.5e-34, 5e-19 of that cos: the quad
    // start keeps a few long-double ulps there (observed 9.6e-20 of p_psi against the truth at
    // 60 digits; GiNaC's 30-digit start, 0). Rounded to double, the same but for ~1 in 1000.
    scene_spec near = scene;
    near.angles[1] = std::nextafter(scene.angles[1], 0.0);
    const start_values w{near.angles, near.initial_rates, near.parameters};
    const long double p_quad = quad.kinematics(*quad.programs_for(w), w).p[2];
    const long double p_ginac = initial_kinematics_of(near, d).p[2];
    GiNaC::exmap at;
    const auto& s = symbols();
    for (int i = 0; i < 3; ++i) {
        at[s.q[i]] = exact_scene_value(near.angles[i], near.angles_written[i]);
        at[s.qd[i]] = exact_scene_value(near.initial_rates[i], near.rates_written[i]);
    }
    for (std::size_t j = 0; j < near.parameters.size(); ++j)
        at[near.model.parameters[j].symbol] = exact_scene_value(near.parameters[j], {});
    const scoped_digits digits(60);
    const long double truth = to_long_double(d.momenta[2].subs(at));
    INFO("p_psi " << static_cast<double>(truth));
    CHECK(std::abs(p_quad - truth) <= 5e-19L * std::abs(truth));
    CHECK(std::abs(p_ginac - truth) <= 1e-19L * std::abs(truth));
    CHECK(static_cast<double>(p_quad) == static_cast<double>(truth));
}

#endif
