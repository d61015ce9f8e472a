// rotgen emit --outputs taylor: the emitted Taylor coefficients, compiled and called, against
// GiNaC's series expansion of the same rates (an independent route: GiNaC expands f(t0 + tau,
// y(tau)) with y(tau) the emitted polynomial, and y' = f asks f^[k] = (k + 1) y^[k+1]). The finite-
// difference route, on every shipped model and form, is in tests/kernels/test_emit_taylor.cpp.
#include "emit_support.hpp"
#include "support.hpp"

#include "run/compile_cache.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace rotgen;
using namespace rotgen::test;

namespace {

struct taylor_case {
    std::string model;
    form_kind form;
};

// The coefficients 0..order of every series, from the compiled taylor() at (t0, y0), or from
// taylor_fixed<8> (fixed: order 8, the recurrences unrolled, the products that only a rate reads
// computed inside the rate).
std::vector<double> emitted_coefficients(const model_spec& spec, const form_expressions& f,
                                         const kernel_request& request, double t0,
                                         const std::vector<double>& y0, int order, bool fixed) {
    const emitted_header h = emit_header(spec, lower_form(spec, f, request), {"test", ""});
    const std::string ns = "rotgen::models::" + h.unit;
    const std::string call = fixed ? "taylor_fixed<8>(t, c, p)" : "taylor(t, c, order, p)";
    const std::string shim = "\nextern \"C\" unsigned long rotgen_test_series() { return " + ns +
                             "::taylor_series; }\n"
                             "extern \"C\" void rotgen_test_taylor(double t, double* c, int order) "
                             "{ (void)order; " +
                             ns + "::params<double> p; " + ns + "::" + call + "; }\n";
    const loaded_library lib = compile_and_load(h.text + shim, "test_taylor_" + h.unit);
    const auto series = reinterpret_cast<unsigned long (*)()>(lib.symbol("rotgen_test_series"))();
    const auto taylor =
        reinterpret_cast<void (*)(double, double*, int)>(lib.symbol("rotgen_test_taylor"));
    const std::size_t m = static_cast<std::size_t>(order) + 1;
    std::vector<double> c(series * m, 0.0);
    for (std::size_t i = 0; i < y0.size(); ++i)
        c[i * m] = y0[i];
    taylor(t0, c.data(), order);
    return c;
}

} // namespace

TEST_CASE("taylor coefficients agree with GiNaC's series expansion of the rates", "[emit]") {
    const taylor_case tc =
        GENERATE(values<taylor_case>({{"heavy_top", form_kind::lagrangian},
                                      {"heavy_top", form_kind::hamiltonian},
                                      {"damped_driven_top", form_kind::body},
                                      {"cube_on_corner", form_kind::body},
                                      {"free_asymmetric_top", form_kind::body}}));
    const bool fixed = GENERATE(false, true);
    CAPTURE(tc.model, to_string(tc.form), fixed);
    const model_spec spec = load_model(model_path(tc.model));
    const derivation d = derive(spec);
    const kernel_request request{{"rhs", "taylor"}, false, {}};
    const form_expressions f =
        build_requested_form(spec, d, tc.form, lagrangian_strategy::explicit_inverse, request);
    const std::size_t n = f.state.size();
    std::vector<double> y0(n);
    for (std::size_t i = 0; i < n; ++i)
        y0[i] = 0.3 + 0.17 * double(i); // theta = 0.47 in the Euler-angle forms
    if (n == 7) {                       // a unit quaternion, then omega
        const double q[4] = {0.9, 0.3, -0.2, 0.1}, norm = std::sqrt(0.95);
        for (int i = 0; i < 4; ++i)
            y0[static_cast<std::size_t>(i)] = q[i] / norm;
    }
    const double t0 = 0.7;
    const int order = 8; // taylor_fixed<8> where fixed
    const std::size_t m = order + 1;
    const std::vector<double> c = emitted_coefficients(spec, f, request, t0, y0, order, fixed);

    const GiNaC::symbol tau("tau");
    GiNaC::exmap at;
    for (std::size_t i = 0; i < n; ++i) {
        GiNaC::ex poly = 0;
        for (std::size_t k = 0; k < m; ++k)
            poly += GiNaC::numeric(c[i * m + k]) * GiNaC::pow(tau, static_cast<int>(k));
        at[f.state[i].symbol] = poly;
    }
    for (const auto& p : f.parameters)
        at[p.symbol] = GiNaC::numeric(p.value);
    at[f.time] = GiNaC::numeric(t0) + tau;
    double worst = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const GiNaC::ex s =
            GiNaC::series_to_poly(f.rates[i].subs(at).series(tau == 0, order)).expand();
        std::vector<double> expected(m - 1);
        double scale = 1;
        for (std::size_t k = 0; k + 1 < m; ++k) {
            expected[k] =
                GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(s.coeff(tau, int(k)))).to_double();
            scale = std::max(scale, std::abs(expected[k]));
        }
        for (std::size_t k = 0; k + 1 < m; ++k) {
            const double emitted = double(k + 1) * c[i * m + k + 1];
            worst = std::max(worst, std::abs(emitted - expected[k]) / scale);
        }
    }

    // observed: worst relative difference 1.8e-16 .. 1.5e-15 (rounding in both routes)
    CHECK(worst < 1e-14);
}

TEST_CASE("taylor refuses a function its recurrences do not cover", "[emit]") {
    const model_spec spec =
        parse_model(YAML::Load("name: tan_top\nparameters: {I1: 1, I3: 2}\ninertia: [I1, I1, I3]\n"
                               "potential: tan(theta)\n"),
                    "tan_top.yaml", "");
    const derivation d = derive(spec);
    const kernel_request request{{"taylor"}, false, {}};
    const form_expressions f =
        build_requested_form(spec, d, form_kind::hamiltonian, lagrangian_strategy::solve, request);
    const lowered_form lf = lower_form(spec, f, request);
    REQUIRE_THROWS_WITH(emit_header(spec, lf, {"test", ""}),
                        "the Taylor recurrences do not cover 'tan' (in the rates)");
}
