// The driver's composable pieces: the stepper concept (every shipped stepper models it, broken
// types do not), observers that stop a run (status, time reached, samples delivered, the state
// left behind), the invariant monitor against a hand-computed drift, and the chart-switch
// predicate.
#include <catch2/catch.hpp>

#include "rotgen.hpp"

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

using namespace rotgen;

namespace {

// ---- the stepper concept, checked at compile time --------------------------------------------

struct dyn_system {
    std::size_t size() const { return 2; }
    void rhs(double, const double* y, double* d) const { d[0] = y[1], d[1] = -y[0]; }
};
struct static_system {
    static constexpr std::size_t state_size = 2;
    void rhs(double, const double* y, double* d) const { d[0] = y[1], d[1] = -y[0]; }
};

template <template <class> class M> constexpr bool models_on_both_sizes() {
    return is_stepper_v<typename M<double>::template stepper<static_system>> &&
           is_stepper_v<typename M<double>::template stepper<dyn_system>> &&
           is_stepper_v<typename M<float>::template stepper<dyn_system>> && is_method_v<M<double>>;
}
static_assert(models_on_both_sizes<rk4>());
static_assert(models_on_both_sizes<dopri5>());
static_assert(models_on_both_sizes<dop853>());
static_assert(models_on_both_sizes<implicit_midpoint>());
static_assert(models_on_both_sizes<rodas4>());
static_assert(check_stepper<dop853_stepper<double, static_system>>());

// The declared properties the driver reads.
static_assert(rk4_stepper<double, static_system>::order == 4 &&
              !rk4_stepper<double, static_system>::error_estimate &&
              rk4_stepper<double, static_system>::dense_output == dense_kind::hermite);
static_assert(dopri5_stepper<double, static_system>::order == 5 &&
              dopri5_stepper<double, static_system>::dense_order == 4 &&
              dopri5_stepper<double, static_system>::dense_output ==
                  dense_kind::continuous_extension);
static_assert(dop853_stepper<double, static_system>::dense_order == 7);
static_assert(implicit_midpoint_stepper<double, static_system>::uses_jacobian &&
              rodas4_stepper<double, static_system>::uses_jacobian &&
              rodas4_stepper<double, static_system>::error_estimate);

// A complete (if useless) stepper, and copies of it that each lack one part.
template <bool Attempt, bool Ends, bool Props> struct toy_stepper {
    using scalar = double;
    using system_type = static_system;
    using vector = state_vector<double, static_system>;
    static constexpr int order = Props ? 1 : 0; // order 0 is not a method
    static constexpr bool error_estimate = false;
    static constexpr dense_kind dense_output = dense_kind::hermite;
    static constexpr int dense_order = 3;
    static constexpr bool uses_jacobian = false;
    bool start(const static_system&, double, const vector&, step_stats&) { return true; }
    template <bool A = Attempt, std::enable_if_t<A, int> = 0>
    step_outcome<double> attempt(const static_system&, double, const vector&, double, step_stats&,
                                 bool) {
        return {status::ok, 0.0};
    }
    bool accept(const static_system&, step_stats&, bool) { return true; }
    const vector& y_new() const { return m_y; }
    const vector& f_start() const { return m_y; }
    template <bool E = Ends, std::enable_if_t<E, int> = 0>
    step_ends<double, vector> hermite_ends() const {
        return {0.0, m_y, m_y, m_y, m_y};
    }
    vector m_y;
};
static_assert(is_stepper_v<toy_stepper<true, true, true>>);
static_assert(!is_stepper_v<toy_stepper<false, true, true>>, "no attempt(): not a stepper");
static_assert(!is_stepper_v<toy_stepper<true, false, true>>, "hermite without hermite_ends()");
static_assert(!is_stepper_v<toy_stepper<true, true, false>>, "order 0");
static_assert(!is_stepper_v<int> && !is_stepper_v<static_system>);
static_assert(!is_method_v<int>);

auto oscillator() { // y'' = −y: y = (cos t, −sin t) from (1, 0)
    return make_system<double, 2>([](double, const double* y, double* d) {
        d[0] = y[1];
        d[1] = -y[0];
    });
}

std::vector<double> grid(double step, int n) { // step, 2·step, …, n·step
    std::vector<double> t;
    for (int i = 1; i <= n; ++i)
        t.push_back(step * i);
    return t;
}

} // namespace

TEST_CASE("an observer returning false stops the run at that sample", "[driver][observer]") {
    const auto sys = oscillator();
    const std::vector<double> times = grid(0.1, 10);
    SECTION("inside a step (dense output), adaptive DOP853") {
        dop853<double> m(1e-12, 1e-12);
        state_vector<double, decltype(sys)> y(1.0, 0.0), seen;
        std::vector<double> ts;
        const auto r = integrate(sys, m, 0.0, y, times, [&](double t, const auto& s) {
            ts.push_back(t);
            seen = s;
            return ts.size() < 4; // stop after the 4th sample, t = 0.4
        });
        CHECK(r.code == status::stopped_by_observer);
        CHECK(std::string(status_name(r.code)) == "stopped_by_observer");
        CHECK(r.t == 0.4);
        CHECK(ts == std::vector<double>{0.1, 0.2, 0.30000000000000004, 0.4});
        CHECK(y == seen); // the state delivered at the stop, exactly
        CHECK_THAT(y[0], Catch::Matchers::WithinAbs(std::cos(0.4), 1e-10));
        CHECK_THAT(y[1], Catch::Matchers::WithinAbs(-std::sin(0.4), 1e-10));
        CHECK(r.stats.accepted > 0);
    }
    SECTION("at a step boundary, fixed-step RK4 on the sample grid") {
        rk4<double> m;
        m.step = 0.1;
        state_vector<double, decltype(sys)> y(1.0, 0.0);
        int calls = 0;
        const auto r =
            integrate(sys, m, 0.0, y, times, [&](double, const auto&) { return ++calls != 3; });
        CHECK(r.code == status::stopped_by_observer);
        CHECK(calls == 3);
        CHECK(r.t == 0.30000000000000004); // grid point t0 + 3·h = the third sample
        CHECK(r.stats.accepted == 3);
        CHECK_THAT(y[0], Catch::Matchers::WithinAbs(std::cos(0.3), 1e-6));
    }
    SECTION("at the start time: no step is taken") {
        rk4<double> m;
        m.step = 0.1;
        state_vector<double, decltype(sys)> y(1.0, 0.0);
        const std::vector<double> with_t0{0.0, 0.5, 1.0};
        const auto r =
            integrate(sys, m, 0.0, y, with_t0, [](double, const auto&) { return false; });
        CHECK(r.code == status::stopped_by_observer);
        CHECK(r.t == 0.0);
        CHECK(r.stats.steps == 0);
        CHECK(y[0] == 1.0);
    }
    SECTION("a void observer and an observer always returning true run to the end") {
        auto m = make_method<double>("dopri5", 1e-9, 1e-9, 0.0);
        REQUIRE(m);
        state_vector<double, decltype(sys)> y1(1.0, 0.0), y2(1.0, 0.0);
        int n1 = 0, n2 = 0;
        const auto r1 = integrate(sys, *m, 0.0, y1, times, [&](double, const auto&) { ++n1; });
        const auto r2 = integrate(sys, *m, 0.0, y2, times, [&](double, const auto&) {
            ++n2;
            return true;
        });
        CHECK(r1.ok());
        CHECK(r2.ok());
        CHECK(n1 == 10);
        CHECK(n2 == 10);
        CHECK(y1 == y2);
        CHECK(r1.t == 1.0);
    }
}

TEST_CASE("observe_all calls every observer and stops when one asks to", "[driver][observer]") {
    const auto sys = oscillator();
    dopri5<double> m(1e-9, 1e-9);
    state_vector<double, decltype(sys)> y(1.0, 0.0);
    int a = 0, b = 0;
    auto count_b = [&](double, const auto&) { ++b; };
    const auto r = integrate(sys, m, 0.0, y, grid(0.1, 10),
                             observe_all([&](double, const auto&) { return ++a < 5; }, count_b));
    CHECK(r.code == status::stopped_by_observer);
    CHECK(a == 5);
    CHECK(b == 5); // the other observer saw the stopping sample too
    CHECK_THAT(r.t, Catch::Matchers::WithinAbs(0.5, 1e-15));
}

TEST_CASE("invariant monitor: first value and max drift", "[driver][monitor]") {
    using vec = Eigen::VectorXd;
    SECTION("by hand") {
        invariant_monitor<double, vec> mon;
        mon.add([](double, const vec& y) { return y[0]; });
        mon.add([](double t, const vec& y) { return t * y[1]; });
        mon(0.0, vec::Constant(2, 1.0));            // v = (1, 0)
        mon(1.0, (vec(2) << 3.0, -2.0).finished()); // v = (3, −2): drifts 2, 2
        mon(2.0, (vec(2) << 0.5, 0.25).finished()); // v = (0.5, 0.5): drifts 0.5, 0.5
        CHECK(mon.samples() == 3);
        CHECK(mon.first(0) == 1.0);
        CHECK(mon.first(1) == 0.0);
        CHECK(mon.max_drift(0) == 2.0);
        CHECK(mon.max_drift(1) == 2.0);
        CHECK(mon.last(0) == 0.5);
        const double nan = std::numeric_limits<double>::quiet_NaN();
        mon.record(std::vector<double>{nan, 0.0});
        mon.record(std::vector<double>{1.0, 9.0});
        CHECK(std::isnan(mon.max_drift(0))); // a NaN is not hidden by later finite values
        CHECK(mon.max_drift(1) == 9.0);
        mon.reset();
        CHECK(mon.samples() == 0);
        CHECK(mon.max_drift(0) == 0.0);
    }
    SECTION("RK4 energy drift on the oscillator, against |R(ih)|^2") {
        // RK4 on y'' = −y multiplies the energy by |R(ih)|² = 1 − h⁶/72 + h⁸/576 each step,
        // R(z) = 1 + z + z²/2 + z³/6 + z⁴/24; so after k steps E = E0·|R|^(2k), monotone.
        const auto sys = oscillator();
        rk4<double> m;
        m.step = 0.1;
        state_vector<double, decltype(sys)> y(1.0, 0.0);
        using state = state_vector<double, decltype(sys)>;
        invariant_monitor<double, state> mon(
            {[](double, const state& s) { return (s[0] * s[0] + s[1] * s[1]) / 2; }});
        std::vector<double> times{0.0};
        for (double t : grid(0.1, 20))
            times.push_back(t);
        const auto r = integrate(sys, m, 0.0, y, times, std::ref(mon));
        REQUIRE(r.ok());
        const double h = 0.1, r2 = 1 - std::pow(h, 6) / 72 + std::pow(h, 8) / 576;
        CHECK(mon.samples() == 21);
        CHECK(mon.first(0) == 0.5);
        CHECK_THAT(mon.max_drift(0),
                   Catch::Matchers::WithinRel(0.5 * (1 - std::pow(r2, 20)), 1e-6));
    }
}

TEST_CASE("chart_switch stops at the first sample after the first with |sin theta| small",
          "[driver][chart]") {
    using vec = Eigen::Vector2d;
    SECTION("by hand") {
        chart_switch<double> leave(1, 0.1, 10.0);
        CHECK(leave(0.0, vec(0.0, 0.01))); // the first sample is exempt
        CHECK(leave(1.0, vec(0.0, 0.5)));  // |sin| = 0.48
        CHECK_FALSE(leave.triggered());
        CHECK_FALSE(leave(2.0, vec(0.0, M_PI - 0.05))); // |sin| = 0.05 near theta = pi
        CHECK(leave.triggered());
        CHECK(leave.time() == 2.0);
        CHECK_THAT(leave.sin_theta(), Catch::Matchers::WithinAbs(std::sin(0.05), 1e-15));
        chart_switch<double> at_end(1, 0.1, 10.0);
        CHECK(at_end(0.0, vec(0.0, 1.0)));
        CHECK(at_end(10.0, vec(0.0, 0.0))); // the end time: nothing left to switch for
        CHECK_FALSE(at_end.triggered());
    }
    SECTION("composed with a recorder in a run through theta = 0") {
        // (phi, theta)' = (1, −1) from (0, 1): theta = 1 − t crosses 0 at t = 1
        const auto sys = make_system<double, 2>([](double, const double*, double* d) {
            d[0] = 1.0;
            d[1] = -1.0;
        });
        rk4<double> m;
        m.step = 0.05;
        state_vector<double, decltype(sys)> y(0.0, 1.0);
        std::vector<double> times{0.0};
        for (double t : grid(0.1, 20))
            times.push_back(t);
        chart_switch<double> leave(1, 0.05, 2.0);
        std::vector<double> recorded;
        const auto r = integrate(
            sys, m, 0.0, y, times,
            observe_all([&](double t, const auto&) { recorded.push_back(t); }, std::ref(leave)));
        CHECK(r.code == status::stopped_by_observer);
        CHECK(leave.triggered());
        CHECK_THAT(r.t, Catch::Matchers::WithinAbs(1.0, 1e-14)); // theta(0.9) = 0.1 >= 0.05
        CHECK(recorded.size() == 11);
        CHECK_THAT(y[1], Catch::Matchers::WithinAbs(0.0, 1e-14));
    }
}
