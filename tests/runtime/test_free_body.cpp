// The exact free rigid-body flow (runtime/free_body/): body momentum and attitude after one long
// step, against independent truth: the elliptic solution of exact_free_top.hpp (ω) and a DOP853
// run in long double at rtol 1e-17 on q̇ = ½ q ⊗ (0, ω), ṁ = m × ω (ω and attitude). Every branch
// of the flow is exercised: both sides of the separatrix, close to it (m > 0.999 and mc ~ 1e-10),
// moments in any order, the symmetric top (both pairs), the sphere and a spin about an axis; the
// phase integrals by Carlson's forms and, for m <= 0.03, by the series of small_parameter.hpp.
#include <catch2/catch.hpp>

#include "exact_free_top.hpp"
#include "free_body/flow.hpp"
#include "rotgen.hpp"

#include <array>
#include <cmath>

using namespace rotgen;

namespace {

using ld = long double;

struct body_result {
    Eigen::Quaterniond q;
    Eigen::Vector3d m;
};

// The reference: Euler's equations and q̇ = ½ q ⊗ (0, ω) by DOP853 in long double.
body_result dop853_reference(std::array<double, 3> in, Eigen::Quaterniond q0, Eigen::Vector3d m0,
                             double t_end) {
    const std::array<ld, 3> i = {in[0], in[1], in[2]};
    auto sys = make_system<ld, 7>([i](ld, const ld* y, ld* d) {
        const ld w[3] = {y[4] / i[0], y[5] / i[1], y[6] / i[2]};
        d[0] = -(y[1] * w[0] + y[2] * w[1] + y[3] * w[2]) / 2;
        d[1] = (y[0] * w[0] + y[2] * w[2] - y[3] * w[1]) / 2;
        d[2] = (y[0] * w[1] + y[3] * w[0] - y[1] * w[2]) / 2;
        d[3] = (y[0] * w[2] + y[1] * w[1] - y[2] * w[0]) / 2;
        d[4] = y[5] * w[2] - y[6] * w[1];
        d[5] = y[6] * w[0] - y[4] * w[2];
        d[6] = y[4] * w[1] - y[5] * w[0];
    });
    Eigen::Matrix<ld, 7, 1> y;
    y << q0.w(), q0.x(), q0.y(), q0.z(), m0[0], m0[1], m0[2];
    dop853<ld> method(1e-17L, 1e-17L);
    method.max_steps = 10000000;
    const auto r = integrate(sys, method, 0.0L, y, static_cast<ld>(t_end));
    REQUIRE(r.code == status::ok);
    body_result out;
    out.q = Eigen::Quaterniond(double(y[0]), double(y[1]), double(y[2]), double(y[3]));
    out.q.normalize();
    out.m = Eigen::Vector3d(double(y[4]), double(y[5]), double(y[6]));
    return out;
}

body_result exact_flow(std::array<double, 3> in, Eigen::Quaterniond q, Eigen::Vector3d m,
                       double t) {
    const free_body_flow<double> flow(in);
    flow.advance(q, m, t);
    return {q, m};
}

double attitude_error(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
    return orientation_error<double>(matrix_from_quaternion(a), matrix_from_quaternion(b));
}

const Eigen::Quaterniond tilted = quaternion_from_euler(0.3, 1.1, -0.7);

} // namespace

TEST_CASE("free flow from t 0 to 100 matches the elliptic solution and DOP853", "[free_body]") {
    // I = (1, 2, 3), omega0 = (1, 0.1, 0.5): G^2 < 2T I2, the polhode circles axis 1
    const std::array<double, 3> in = {1, 2, 3};
    const Eigen::Vector3d w0(1, 0.1, 0.5);
    const Eigen::Vector3d m0(w0[0], 2 * w0[1], 3 * w0[2]);
    const auto got = exact_flow(in, tilted, m0, 100);
    const free_top_exact<ld> exact({1, 2, 3}, {1, 0.1L, 0.5L});
    const auto w = exact(100);
    for (int i = 0; i < 3; ++i) // observed 2.2e-15
        CHECK(std::abs(got.m[i] / in[i] - double(w[i])) < 2e-14);
    const auto ref = dop853_reference(in, tilted, m0, 100);
    CHECK(attitude_error(got.q, ref.q) < 1e-13);          // observed 1.7e-14
    CHECK((got.m - ref.m).cwiseAbs().maxCoeff() < 5e-14); // observed 6.7e-15
}

TEST_CASE("free flow in every regime agrees with DOP853 at rtol 1e-17", "[free_body]") {
    struct free_case {
        const char* what;
        std::array<double, 3> inertia;
        std::array<double, 3> m0;
        double t;
        double bound; // on the attitude angle and |Δm|/|m|, about 10x the observed error
    };
    // clang-format off
    const auto c = GENERATE(values<free_case>({
        {"polhode about the largest axis, m = 0.038 (Carlson)", {1, 2, 3}, {0.2, 0.4, 2.5}, 60, 5e-14}, // 6.4e-15
        {"moments in another order", {2, 3, 1}, {0.4, 2.5, 0.2}, 60, 5e-14}, // 6.6e-15
        {"odd permutation of the moments", {3, 2, 1}, {2.5, 0.4, -0.2}, 60, 5e-14}, // 6.4e-15
        {"negative components", {1, 2, 3}, {-1, -0.2, -1.5}, 60, 8e-14}, // 9.3e-15
        {"near the separatrix, mc = 3.8e-4", {1, 2, 3}, {1, 0.5, 1.732397217730391}, 30, 1e-13}, // 1.0e-14
        {"at the separatrix, mc = 1.9e-10", {1, 2, 3}, {1, 0.5, 1.7320508077420822}, 20, 3e-11}, // 9.9e-12
        {"symmetric top I1 = I2", {1, 1, 0.5}, {0.3, -0.2, 5}, 50, 3e-14}, // 3.7e-15
        {"symmetric top I2 = I3", {0.5, 1, 1}, {5, 0.3, -0.2}, 50, 3e-14}, // 4.3e-15
        {"nearly symmetric, I2 = I1 (1 + 1e-12)", {1, 1 + 1e-12, 0.5}, {0.3, -0.2, 5}, 50, 5e-13}, // 6.2e-14
        {"sphere", {2, 2, 2}, {0.3, -0.2, 1}, 50, 3e-14}, // 4.0e-15
        {"spin about the intermediate axis", {1, 2, 3}, {0, 2, 0}, 50, 3e-15}, // 3.4e-16
        {"fast spin, small nutation", {1, 1.2, 0.5}, {1e-3, 2e-3, 500}, 1, 3e-13}, // 7.2e-14 (series)
        {"m = 0.022: the series near its limit", {1, 1.2, 0.5}, {0.75, 0.6, 2.5}, 60, 1.5e-13}, // 1.5e-14
    }));
    // clang-format on
    INFO(c.what);
    const Eigen::Vector3d m0(c.m0[0], c.m0[1], c.m0[2]);
    const auto got = exact_flow(c.inertia, tilted, m0, c.t);
    const auto ref = dop853_reference(c.inertia, tilted, m0, c.t);
    const double scale = m0.norm();
    CHECK(attitude_error(got.q, ref.q) < c.bound);
    CHECK((got.m - ref.m).cwiseAbs().maxCoeff() < c.bound * scale); // relative: below the angle's
}

TEST_CASE("free flow composes: advancing by h1 then h2 equals advancing by h1 + h2",
          "[free_body]") {
    // the group property of an exact flow; an error in the phase or the precession bookkeeping
    // across half periods (u0, W over 2K) shows here at the size of the phase itself
    const std::array<double, 3> in = {1, 1.2, 0.5};
    const Eigen::Vector3d m0(0.3, -0.8, 4);
    const auto once = exact_flow(in, tilted, m0, 7.3);
    const auto first = exact_flow(in, tilted, m0, 2.9);
    const auto both = exact_flow(in, first.q, first.m, 4.4);
    CHECK(attitude_error(once.q, both.q) < 1e-13);          // observed 1.1e-14
    CHECK((once.m - both.m).cwiseAbs().maxCoeff() < 3e-14); // 3.2e-15
    const auto back = exact_flow(in, once.q, once.m, -7.3); // and it is reversible
    CHECK(attitude_error(back.q, tilted) < 7e-14);          // 1.4e-14
    CHECK((back.m - m0).cwiseAbs().maxCoeff() < 2e-14);     // 1.6e-15
}

TEST_CASE("3e4 short free flows of an asymmetric body compose to one long one", "[free_body]") {
    // regression: the elliptic formulas keep |m| to a few eps a call only, and a drift in |m| is a
    // drift in the spin rate (1.5e-11 here before keep_norm in flow.hpp, 1.7e-12 after)
    const std::array<double, 3> in = {1, 1.2, 0.5};
    const Eigen::Vector3d m0(0.3, -0.2, 50);
    auto many = body_result{tilted, m0};
    const free_body_flow<double> flow(in);
    for (int k = 0; k < 30000; ++k)
        flow.advance(many.q, many.m, 10.0 / 30000);
    const auto once = exact_flow(in, tilted, m0, 10);
    CHECK(attitude_error(many.q, once.q) < 5e-12); // observed 1.7e-12
}
