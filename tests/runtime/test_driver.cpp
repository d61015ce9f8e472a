// The common driver: status values for blow-ups, budgets and bad arguments; sample handling;
// backward integration; work counters; scalar types; the system adapters (lambda, run-time
// size, generated model namespace) and the run-time method choice.
#include <catch2/catch.hpp>

#include "rotgen.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace rotgen;

// A stand-in for a generated model header (same shape as the emitter's output).
namespace mock_model {
template <class T> struct params { T omega = T(2); };
constexpr std::size_t state_size = 2;
template <class T> void rhs(T, const T* y, T* dydt, const params<T>& p) {
    dydt[0] = y[1];
    dydt[1] = -p.omega * p.omega * y[0];
}
template <class T> void jacobian(T, const T*, T* j, const params<T>& p) {
    j[0] = T(0), j[1] = T(1), j[2] = -p.omega * p.omega, j[3] = T(0);
}
template <class T> T energy(const T* y, const params<T>& p) {
    return (y[1] * y[1] + p.omega * p.omega * y[0] * y[0]) / T(2);
}
} // namespace mock_model

namespace {

auto blow_up() { // y' = y², y(0) = 1: y = 1/(1 − t), infinite at t = 1
    return make_system<double, 1>([](double, const double* y, double* d) { d[0] = y[0] * y[0]; },
                                  [](double, const double* y, double* j) { j[0] = 2 * y[0]; });
}

template <class T> auto oscillator() {
    return make_system<T, 2>(
        [](T, const T* y, T* d) {
            d[0] = y[1];
            d[1] = -y[0];
        },
        [](T, const T*, T* j) { j[0] = T(0), j[1] = T(1), j[2] = T(-1), j[3] = T(0); });
}

// A system with a run-time size and no Jacobian: n uncoupled decays y_i' = −(i+1) y_i.
struct decay_chain {
    std::size_t n;
    std::size_t size() const { return n; }
    void rhs(double, const double* y, double* d) const {
        for (std::size_t i = 0; i < n; ++i)
            d[i] = -double(i + 1) * y[i];
    }
};

} // namespace

TEST_CASE("blow-up y' = y^2 past t = 1 ends with step_size_underflow or non_finite, not a crash",
          "[status]") {
    const auto sys = blow_up();
    // The adaptive methods shrink the step as the pole is approached until |h| < 16·eps·|t|.
    // The numerical solution has its own pole, within O(rtol) of t = 1 (1e-9 … 2e-9 after
    // t = 1 at rtol 1e-8), so the run stops within 1e-6 of t = 1 with a huge, finite state.
    auto check = [](const integration_result<double>& r, double y) {
        INFO(status_name(r.code) << ": " << r.message << ", y = " << y);
        CHECK((r.code == status::step_size_underflow || r.code == status::non_finite));
        CHECK_FALSE(r.message.empty());
        CHECK(std::abs(r.t - 1.0) < 1e-6);
        CHECK(std::isfinite(y));
        CHECK(y > 1e9); // it really got to the pole
    };
    SECTION("dopri5") {
        Eigen::Matrix<double, 1, 1> y(1.0);
        const auto r = integrate(sys, dopri5<double>(1e-8, 1e-8), 0.0, y, 2.0);
        check(r, y[0]);
    }
    SECTION("dop853") {
        Eigen::Matrix<double, 1, 1> y(1.0);
        const auto r = integrate(sys, dop853<double>(1e-8, 1e-8), 0.0, y, 2.0);
        check(r, y[0]);
    }
    SECTION("rodas4") {
        Eigen::Matrix<double, 1, 1> y(1.0);
        rodas4<double> m(1e-8, 1e-8);
        m.autonomous = true;
        const auto r = integrate(sys, m, 0.0, y, 2.0);
        check(r, y[0]);
    }
    SECTION("rk4 (fixed step): overflow to Inf stops at the last finite state") {
        Eigen::Matrix<double, 1, 1> y(1.0);
        rk4<double> m;
        m.step = 0.01;
        const auto r = integrate(sys, m, 0.0, y, 2.0);
        CHECK(r.code == status::non_finite);
        CHECK(std::isfinite(y[0]));
        CHECK(r.t > 1.0); // RK4 steps over the pole and overflows a few steps later
        CHECK(r.t < 2.0);
    }
}

TEST_CASE("a non-finite initial state or f(t0, y0) gives non_finite", "[status]") {
    const auto sys =
        make_system<double, 1>([](double, const double* y, double* d) { d[0] = std::sqrt(y[0]); });
    Eigen::Matrix<double, 1, 1> y(-1.0);
    const auto r = integrate(sys, dopri5<double>(), 0.0, y, 1.0);
    CHECK(r.code == status::non_finite);
    CHECK(r.t == 0.0);
    Eigen::Vector2d y_nan(std::numeric_limits<double>::quiet_NaN(), 0.0);
    const auto r2 = integrate(oscillator<double>(), rk4<double>{0.1}, 0.0, y_nan, 1.0);
    CHECK(r2.code == status::non_finite);
    CHECK_THAT(r2.message, Catch::Matchers::Contains("initial state"));
    Eigen::Vector2d y_inf(std::numeric_limits<double>::infinity(), 0.0);
    const auto r3 = integrate(oscillator<double>(), dop853<double>(), 0.0, y_inf, 1.0);
    CHECK(r3.code == status::non_finite);
    CHECK(r3.stats.rhs_evals == 0);
}

TEST_CASE(
    "a right-hand side that turns NaN on the way stops with non_finite at the last good state",
    "[status]") {
    // y' = −1 while y >= 0.5, NaN below: the solution 1 − t leaves the domain at t = 0.5
    const auto sys = make_system<double, 1>([](double, const double* y, double* d) {
        d[0] = y[0] >= 0.5 ? -1.0 : std::numeric_limits<double>::quiet_NaN();
    });
    SECTION("adaptive: trial steps into the NaN region are rejected until the step underflows") {
        Eigen::Matrix<double, 1, 1> y(1.0);
        const auto r = integrate(sys, dopri5<double>(1e-8, 1e-8), 0.0, y, 1.0);
        INFO(r.message);
        CHECK(r.code == status::non_finite);
        CHECK(r.stats.rejected > 0);
        CHECK(r.t <= 0.5);
        CHECK(r.t > 0.5 - 1e-9);
        CHECK(y[0] == Approx(1.0 - r.t).epsilon(1e-12));
    }
    SECTION("fixed step: the first non-finite step stops the run") {
        Eigen::Matrix<double, 1, 1> y(1.0);
        const auto r = integrate(sys, rk4<double>{0.07}, 0.0, y, 1.0);
        CHECK(r.code == status::non_finite);
        CHECK(r.t == Approx(0.49)); // 7 steps of 0.07; the 8th evaluates f below 0.5
        CHECK(y[0] == Approx(0.51));
    }
}

TEST_CASE("the step budget ends with max_steps at the last good state", "[status]") {
    dopri5<double> m(1e-10, 1e-10);
    m.max_steps = 10;
    Eigen::Vector2d y(1.0, 0.0);
    const auto r = integrate(oscillator<double>(), m, 0.0, y, 1000.0);
    CHECK(r.code == status::max_steps);
    CHECK(r.stats.steps == 10);
    CHECK(r.t > 0.0);
    CHECK(r.t < 1000.0);
    CHECK(y[0] == Approx(std::cos(r.t)).margin(1e-8));
    rk4<double> f{0.1};
    f.max_steps = 5;
    Eigen::Vector2d z(1.0, 0.0);
    const auto rf = integrate(oscillator<double>(), f, 0.0, z, 1.0);
    CHECK(rf.code == status::max_steps);
    CHECK(rf.t == Approx(0.5));
}

TEST_CASE("bad arguments give invalid_argument with a message", "[status]") {
    const auto sys = oscillator<double>();
    Eigen::Vector2d y(1.0, 0.0);
    auto expect_invalid = [&](const integration_result<double>& r, const std::string& word) {
        CHECK(r.code == status::invalid_argument);
        CHECK_THAT(r.message, Catch::Matchers::Contains(word));
        CHECK(r.stats.rhs_evals == 0);
    };
    expect_invalid(integrate(sys, dopri5<double>(-1e-6, 1e-9), 0.0, y, 1.0), "tolerance");
    expect_invalid(integrate(sys, dopri5<double>(1e-20, 1e-9), 0.0, y, 1.0), "rtol");
    expect_invalid(integrate(sys, dop853<double>(0.0, 0.0), 0.0, y, 1.0), "both 0");
    expect_invalid(integrate(sys, rk4<double>{0.0}, 0.0, y, 1.0), "step");
    implicit_midpoint<double> mid;
    expect_invalid(integrate(sys, mid, 0.0, y, 1.0), "step");
    const std::vector<double> unsorted = {0.5, 0.2, 1.0};
    expect_invalid(
        integrate(sys, dopri5<double>(), 0.0, y, unsorted, [](double, const Eigen::Vector2d&) {}),
        "monotone");
    const std::vector<double> nan_time = {0.5, std::nan(""), 1.0};
    expect_invalid(
        integrate(sys, dopri5<double>(), 0.0, y, nan_time, [](double, const Eigen::Vector2d&) {}),
        "not finite");
    const std::vector<double> none;
    expect_invalid(
        integrate(sys, dopri5<double>(), 0.0, y, none, [](double, const Eigen::Vector2d&) {}),
        "no sample");
    Eigen::VectorXd wrong(3);
    wrong.setOnes();
    expect_invalid(integrate(decay_chain{2}, dopri5<double>(), 0.0, wrong, 1.0), "components");
    CHECK(y == Eigen::Vector2d(1.0, 0.0)); // untouched
}

TEST_CASE("samples: every requested time once, in order, initial samples get y0", "[driver]") {
    const auto sys = oscillator<double>();
    const std::vector<double> times = {0.0, 0.0, 0.25, 0.25, 1.0, 3.0, 3.0};
    for (const any_method<double>& m :
         {*make_method<double>("rk4", 0, 0, 0.1), *make_method<double>("dopri5", 1e-9, 1e-9, 0),
          *make_method<double>("dop853", 1e-9, 1e-9, 0),
          *make_method<double>("implicit_midpoint", 0, 0, 0.01),
          *make_method<double>("rodas4", 1e-9, 1e-9, 0)}) {
        Eigen::Vector2d y(1.0, 0.0);
        std::vector<double> seen;
        double worst = 0;
        const auto r = integrate(sys, m, 0.0, y, times, [&](double t, const Eigen::Vector2d& yt) {
            seen.push_back(t);
            worst = std::max(worst, std::abs(yt[0] - std::cos(t)) + std::abs(yt[1] + std::sin(t)));
        });
        REQUIRE(r.ok());
        CHECK(seen == times);
        CHECK(r.t == 3.0);
        CHECK(worst < 2e-3); // loosest: midpoint h = 0.01 (phase error h²t/24 ~ 1e-5)
    }
    // only t0 requested: no step taken
    Eigen::Vector2d y(1.0, 0.0);
    const auto r = integrate(sys, dopri5<double>(), 0.0, y, std::vector<double>{0.0},
                             [](double, const Eigen::Vector2d&) {});
    CHECK(r.ok());
    CHECK(r.stats.steps == 0);
    CHECK_FALSE(make_method<double>("euler", 0, 0, 0).has_value());
}

TEST_CASE("backward integration (end time before the start)", "[driver]") {
    const auto sys =
        make_system<double, 1>([](double, const double* y, double* d) { d[0] = y[0]; });
    for (const any_method<double>& m :
         {*make_method<double>("rk4", 0, 0, 0.01), *make_method<double>("dopri5", 1e-10, 1e-12, 0),
          *make_method<double>("dop853", 1e-10, 1e-12, 0),
          *make_method<double>("rodas4", 1e-10, 1e-12, 0)}) {
        Eigen::Matrix<double, 1, 1> y(std::exp(1.0));
        std::vector<double> times = {0.75, 0.5, 0.0};
        std::vector<double> seen;
        const auto r =
            integrate(sys, m, 1.0, y, times, [&](double t, const Eigen::Matrix<double, 1, 1>& yt) {
                seen.push_back(t);
                CHECK(yt[0] == Approx(std::exp(t)).epsilon(1e-8));
            });
        REQUIRE(r.ok());
        CHECK(seen == times);
        CHECK(r.t == 0.0);
        CHECK(y[0] == Approx(1.0).epsilon(1e-8));
    }
}

TEST_CASE("work counters follow the methods' stage counts", "[driver]") {
    const auto sys = oscillator<double>();
    Eigen::Vector2d y(1.0, 0.0);
    const auto r5 = integrate(sys, dopri5<double>(1e-8, 1e-8), 0.0, y, 10.0);
    REQUIRE(r5.ok());
    CHECK(r5.stats.steps == r5.stats.accepted + r5.stats.rejected);
    CHECK(r5.stats.rhs_evals == 6 * r5.stats.steps + 2); // FSAL: 6 per attempt, f(t0), hinit's one
    CHECK(r5.stats.jac_evals == 0);
    y = Eigen::Vector2d(1.0, 0.0);
    const auto r8 = integrate(sys, dop853<double>(1e-8, 1e-8), 0.0, y, 10.0);
    REQUIRE(r8.ok());
    CHECK(r8.stats.rhs_evals ==
          11 * r8.stats.steps + r8.stats.accepted + 2); // + k13 per accepted step
    y = Eigen::Vector2d(1.0, 0.0);
    const auto rk = integrate(sys, rk4<double>{0.1}, 0.0, y, 10.0);
    CHECK(rk.stats.rhs_evals == 4 * 100);
    y = Eigen::Vector2d(1.0, 0.0);
    rodas4<double> ro(1e-8, 1e-8); // non-autonomous by default: one more f for ∂f/∂t per Jacobian
    const auto rr = integrate(sys, ro, 0.0, y, 10.0);
    REQUIRE(rr.ok());
    CHECK(rr.stats.jac_evals == rr.stats.accepted);
    CHECK(rr.stats.factorisations == rr.stats.steps);
    CHECK(rr.stats.rhs_evals == 5 * rr.stats.steps + 3 * rr.stats.accepted + 2);
}

TEMPLATE_TEST_CASE("every method works in float, double and long double", "[driver][scalar]", float,
                   double, long double) {
    using T = TestType;
    const T eps = std::numeric_limits<T>::epsilon();
    const auto sys = oscillator<T>();
    // adaptive methods at rtol = max(1e-12, 1e3·eps): the global error over 1.6 periods is a
    // small multiple of rtol (tolerance proportionality). Measured (float / double / long double):
    // DOPRI5 2.9 / 2.6 / 2.6 rtol, DOP853 1.2 / 1.4 / 1.4 rtol, RODAS4 2.2 / 2.1 / 2.1 rtol; the
    // bounds are 3.5x to 5x those. Fixed steps h = 0.01 over 1000 steps: truncation C·h^p plus
    // rounding, measured RK4 4.2e-7 (3.5 eps) in float and 7.0e-10 in double and long double,
    // the midpoint rule 7.0e-5 in every type.
    const T rtol = std::max(T(1e-12), T(1000) * eps);
    auto error_of = [&](const auto& m) {
        Eigen::Matrix<T, 2, 1> y(T(1), T(0));
        const auto r = integrate(sys, m, T(0), y, T(10));
        REQUIRE(r.ok());
        return std::max(std::abs(y[0] - std::cos(T(10))), std::abs(y[1] + std::sin(T(10))));
    };
    CHECK(error_of(dopri5<T>(rtol, rtol)) < T(10) * rtol);
    CHECK(error_of(dop853<T>(rtol, rtol)) < T(5) * rtol);
    rodas4<T> ro(rtol, rtol);
    ro.autonomous = true;
    CHECK(error_of(ro) < T(10) * rtol);
    CHECK(error_of(rk4<T>{T(0.01)}) < T(1e-9) + T(40) * eps); // 10·h⁴/120 ≈ 1e-9
    implicit_midpoint<T> mid;
    mid.step = T(0.01);
    CHECK(error_of(mid) < T(1e-4) + T(40) * eps); // phase error t·h²/12 ≈ 8e-5
}

TEST_CASE("generated-model adapter wraps a model namespace into a system", "[system]") {
    auto sys = ROTGEN_GENERATED_SYSTEM_WITH_ENERGY(mock_model, double);
    static_assert(decltype(sys)::state_size == 2);
    static_assert(has_jacobian_v<decltype(sys), double>);
    static_assert(has_energy_v<decltype(sys), double>);
    sys.params.omega = 3.0;
    Eigen::Vector2d y(1.0, 0.0);
    double drift = 0;
    const double e0 = sys.energy(0.0, y.data());
    std::vector<double> times = {0.5, 1.0, 1.5, 2.0};
    const auto r = integrate(sys, rodas4<double>(1e-10, 1e-12), 0.0, y, times,
                             [&](double t, const Eigen::Vector2d& yt) {
                                 drift = std::max(drift, std::abs(sys.energy(t, yt.data()) - e0));
                             });
    REQUIRE(r.ok());
    CHECK(y[0] == Approx(std::cos(6.0)).margin(1e-8));
    CHECK(drift < 1e-7);

    const auto rhs_only = ROTGEN_GENERATED_SYSTEM_RHS(mock_model, double);
    static_assert(!has_jacobian_v<decltype(rhs_only), double>);
    static_assert(!has_energy_v<decltype(rhs_only), double>);
    Eigen::Vector2d z(1.0, 0.0);
    implicit_midpoint<double> mid; // falls back to a finite-difference Jacobian
    mid.step = 1e-3;
    REQUIRE(integrate(rhs_only, mid, 0.0, z, 1.0).ok());
    CHECK(z[0] == Approx(std::cos(2.0)).margin(1e-5));
}

TEST_CASE("systems with a run-time size use dynamic Eigen vectors", "[system]") {
    const decay_chain sys{4};
    static_assert(state_dim<decay_chain>() == Eigen::Dynamic);
    Eigen::VectorXd y = Eigen::VectorXd::Ones(4);
    rodas4<double> m(1e-9, 1e-12); // no Jacobian: finite differences, 4 extra f each
    m.autonomous = true;
    const auto r = integrate(sys, m, 0.0, y, 2.0);
    REQUIRE(r.ok());
    CHECK(r.stats.jac_evals == r.stats.accepted);
    for (int i = 0; i < 4; ++i)
        CHECK(y[i] == Approx(std::exp(-2.0 * (i + 1))).epsilon(1e-6));
    Eigen::VectorXd z = Eigen::VectorXd::Ones(4);
    REQUIRE(integrate(sys, dop853<double>(1e-10, 1e-12), 0.0, z, 2.0).ok());
    CHECK((z - y).cwiseAbs().maxCoeff() < 1e-7);
}
