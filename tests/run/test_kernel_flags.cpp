// The scalar kernels of a `taylor` scene are compiled for the host's vectors
// (host_exact_vector_flags(), run/compile_cache.hpp) on the promise that they keep the portable
// build's bits: the same emitted source, compiled both ways, must give the same rhs, Jacobian and
// Taylor coefficients to the last bit. With -mfma added (host_vector_flags()) the body form's rhs
// differs in 1,270 of the 2,000 states (GCC 12 fuses an add-subtract into vfmaddsub), so this
// test fails for flags that let the compiler fuse. On a CPU without AVX2 both builds are the
// portable one, and the comparison holds trivially.
#include "emit_support.hpp"
#include "support.hpp"

#include "run/compile_cache.hpp"

#include <catch2/catch.hpp>

#include <cstring>
#include <random>

using namespace rotgen;
using namespace rotgen::test;

namespace {

constexpr int fixed_order = 15; // the heavy-top sweep's order at rtol 1e-12

using kernel = void (*)(double t, const double* y, double* out);

// The header's rhs, jacobian and taylor_fixed<15> at the model's default parameters, exported.
std::string kernel_source(const emitted_header& h) {
    const std::string ns = "rotgen::models::" + h.unit;
    const std::string p = ns + "::params<double> p; ";
    return h.text + "\nextern \"C\" {\n" +
           "void rotgen_test_rhs(double t, const double* y, double* out) { " + p + ns +
           "::rhs(t, y, out, p); }\n" +
           "void rotgen_test_jacobian(double t, const double* y, double* out) { " + p + ns +
           "::jacobian(t, y, out, p); }\n" +
           "void rotgen_test_taylor(double t, const double* y, double* c) { " + p +
           "const unsigned long m = " + std::to_string(fixed_order + 1) +
           "; for (unsigned long i = 0; i < " + ns + "::state_size; ++i) c[i * m] = y[i]; " + ns +
           "::taylor_fixed<" + std::to_string(fixed_order) + ">(t, c, p); }\n}\n";
}

// How many of `states` random states give other bits from the two libraries' `name`.
int differing_states(const loaded_library& a, const loaded_library& b, const char* name,
                     std::size_t n, std::size_t outputs) {
    const auto fa = reinterpret_cast<kernel>(a.symbol(name));
    const auto fb = reinterpret_cast<kernel>(b.symbol(name));
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-2, 2);
    int differ = 0;
    for (int s = 0; s < 2000; ++s) {
        std::vector<double> y(n), oa(outputs, 0.0), ob(outputs, 0.0);
        for (double& v : y)
            v = u(rng);
        y[1] = 0.3 + std::abs(y[1]); // theta away from the gimbal lock (the Euler-angle form)
        fa(0.5, y.data(), oa.data());
        fb(0.5, y.data(), ob.data());
        differ += std::memcmp(oa.data(), ob.data(), outputs * sizeof(double)) != 0;
    }
    return differ;
}

} // namespace

TEST_CASE("taylor kernels built for the host's vectors keep the portable build's bits", "[run]") {
    const form_kind form = GENERATE(form_kind::lagrangian, form_kind::body);
    CAPTURE(to_string(form), host_exact_vector_flags());
    const model_spec spec = load_model(model_path("heavy_top"));
    const kernel_request request{{"rhs", "jacobian", "taylor"}, false, {}};
    const form_expressions f = build_requested_form(spec, derive(spec), form,
                                                    lagrangian_strategy::explicit_inverse, request);
    const emitted_header h = emit_header(spec, lower_form(spec, f, request), {"test", ""});
    const std::string source = kernel_source(h);
    const loaded_library portable = compile_and_load(source, "test_flags_" + h.unit);
    const loaded_library host =
        compile_and_load(source, "test_flags_" + h.unit, host_exact_vector_flags());
    const std::size_t n = f.state.size();
    CHECK(differing_states(portable, host, "rotgen_test_rhs", n, n) == 0);
    CHECK(differing_states(portable, host, "rotgen_test_jacobian", n, n * n) == 0);
    CHECK(differing_states(portable, host, "rotgen_test_taylor", n, 64 * (fixed_order + 1)) == 0);
}
