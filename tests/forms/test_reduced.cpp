// The reduced form's outputs: which it can always give (the ignored rates, the momenta), which it
// never can (the rotation A, which mentions every angle), checked against the heavy top's
// Hamiltonian (5.79) and a free asymmetric top.
#include "support.hpp"

#include "forms/forms.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace rotgen;
using namespace rotgen::test;
using Catch::Matchers::WithinRel;

namespace {

double value_of(const GiNaC::ex& e, const GiNaC::exmap& at) {
    return GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(e.subs(at))).to_double();
}

} // namespace

TEST_CASE("the reduced heavy top's ignored rates are dH/dp of (5.79)", "[forms][reduced]") {
    const model_spec spec = load_model(model_path("heavy_top"));
    const derivation d = derive(spec);
    const form_expressions f =
        build_form(spec, d, form_kind::reduced, lagrangian_strategy::explicit_inverse, false);
    REQUIRE(f.state.size() == 2); // (theta, p_theta)
    REQUIRE(f.outputs.count("ignored_rates") == 1);
    const form_output& ignored = f.outputs.at("ignored_rates");
    REQUIRE(ignored.names == std::vector<std::string>{"phi_dot", "psi_dot"});

    // (5.79): H = p_theta^2/(2 I1) + p_psi^2/(2 I3)
    //              + (p_phi - p_psi cos theta)^2/(2 I1 sin^2 theta) + M g h cos theta,
    // phi_dot = dH/dp_phi, psi_dot = dH/dp_psi.
    const auto& s = symbols();
    const double I1 = 1.0, I3 = 0.5, theta = 0.7, p_phi = 0.3, p_theta = -0.2, p_psi = 1.1;
    GiNaC::exmap at = spec.parameter_defaults();
    at[s.q[1]] = theta;
    at[s.p[0]] = p_phi;
    at[s.p[1]] = p_theta;
    at[s.p[2]] = p_psi;
    const double st2 = std::sin(theta) * std::sin(theta), ct = std::cos(theta);
    const double phi_dot = (p_phi - p_psi * ct) / (I1 * st2);
    const double psi_dot = p_psi / I3 - ct * (p_phi - p_psi * ct) / (I1 * st2);
    CHECK_THAT(value_of(ignored.values[0], at), WithinRel(phi_dot, 1e-12));
    CHECK_THAT(value_of(ignored.values[1], at), WithinRel(psi_dot, 1e-12));
}

TEST_CASE("the reduced form always gives the ignored rates and the momenta, never the rotation",
          "[forms][reduced]") {
    // heavy_top ignores phi and psi, the free asymmetric top phi alone.
    const std::string model = GENERATE("heavy_top", "free_asymmetric_top", "full_tensor_top");
    const model_spec spec = load_model(model_path(model));
    const derivation d = derive(spec);
    const form_expressions f =
        build_form(spec, d, form_kind::reduced, lagrangian_strategy::explicit_inverse, false);
    const auto& s = symbols();
    std::vector<GiNaC::ex> ignored_angles;
    for (const form_parameter& p : f.parameters)
        if (!p.specialisable)
            for (int i = 0; i < 3; ++i)
                if (p.name == "p_" + f.angles.names[i]) ignored_angles.push_back(s.q[i]);
    REQUIRE(!ignored_angles.empty());
    REQUIRE(f.outputs.count("ignored_rates") == 1);
    REQUIRE(f.outputs.count("momenta") == 1);
    CHECK(f.outputs.at("ignored_rates").values.size() == ignored_angles.size());
    for (const GiNaC::ex& rate : f.outputs.at("ignored_rates").values)
        for (const GiNaC::ex& q : ignored_angles)
            CHECK(!rate.has(q));
    CHECK(f.outputs.count("rotation") == 0);
    // phi is cyclic for every body without a phi-dependent potential or torque, and comes first.
    CHECK(f.unavailable.at("rotation") ==
          "it depends on the ignored coordinate phi; use --form hamiltonian");
}
