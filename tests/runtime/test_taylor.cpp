// The Taylor method (steppers/taylor.hpp) on the checked-in generated headers with Taylor
// coefficients: the free top I = (1, 2, 3) against its exact elliptic solution, in double and
// long double; the heavy top against DOP853 and its invariants; dense output; the concept.
#include <catch2/catch.hpp>

#include "exact_free_top.hpp"
#include "integrate/integrate.hpp"
#include "method.hpp"
#include "steppers/dop853.hpp"
#include "steppers/taylor.hpp"
#include "taylor_system.hpp"

#include "free_asymmetric_top_body_taylor.hpp"
#include "heavy_top_taylor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

using namespace rotgen;
namespace free_top = rotgen::models::free_asymmetric_top_body_taylor;
namespace heavy_top = rotgen::models::heavy_top_taylor;

namespace {

// The largest error over 101 samples of t = 0..t_end against the exact solution, and the steps.
template <class T> struct free_top_run {
    T error = 0;
    std::size_t steps = 0;
    status code = status::ok;
};

template <class T> free_top_run<T> run_free_top(T tol, T t_end) {
    const std::array<T, 3> inertia = {1, 2, 3}, w0 = {1, T(0.1L), T(0.5L)};
    const free_top_exact<T> exact(inertia, w0);
    const auto sys = ROTGEN_GENERATED_TAYLOR_SYSTEM(free_top, T);
    taylor<T> m;
    m.rtol = m.atol = tol;
    Eigen::Matrix<T, 3, 1> y(w0[0], w0[1], w0[2]);
    std::vector<T> times;
    for (int i = 1; i <= 100; ++i)
        times.push_back(t_end * T(i) / T(100));
    free_top_run<T> r;
    const auto res = integrate(sys, m, T(0), y, times, [&](T t, const Eigen::Matrix<T, 3, 1>& w) {
        const auto e = exact(t);
        for (int i = 0; i < 3; ++i) {
            using std::abs;
            r.error = std::max(r.error, T(abs(w[i] - e[static_cast<std::size_t>(i)])));
        }
    });
    r.steps = res.stats.steps;
    r.code = res.code;
    return r;
}

} // namespace

TEST_CASE("taylor models the stepper concept and refuses a system without coefficients",
          "[taylor]") {
    STATIC_REQUIRE(check_method<taylor<double>>());
    STATIC_REQUIRE(check_method<taylor<long double>>());
    auto plain = make_system<double, 1>([](double, const double* y, double* d) { d[0] = -y[0]; });
    Eigen::Matrix<double, 1, 1> y(1.0);
    const auto res = integrate(plain, taylor<double>(), 0.0, y, 1.0);
    CHECK(res.code == status::invalid_argument);
    CHECK(res.message == "taylor: the system gives no Taylor coefficients (emit them with "
                         "--outputs taylor)");
    taylor<double> below;
    below.rtol = 1e-17;
    CHECK(below.check() == "a tolerance is below the precision of the scalar type");
}

TEST_CASE("taylor on the free top follows the tolerance, 1e-6 to 1e-15", "[taylor]") {
    // observed (t = 0..20, max over 100 samples, dense output included):
    //   tol 1e-6: 2.1e-8   1e-8: 1.5e-10   1e-10: 3.9e-12   1e-12: 2.8e-14   1e-14: 4.4e-15
    //   1e-15: 1.05e-15 (rounding: the sum of ~45 steps' roundings)
    const auto [tol, bound] = GENERATE(table<double, double>({{1e-6, 2e-7},
                                                              {1e-8, 1.5e-9},
                                                              {1e-10, 4e-11},
                                                              {1e-12, 2.8e-13},
                                                              {1e-14, 4e-14},
                                                              {1e-15, 1e-14}}));
    CAPTURE(tol);
    const auto r = run_free_top<double>(tol, 20.0);
    REQUIRE(r.code == status::ok);
    CHECK(r.error < bound);
    CHECK(r.error > 0);
}

TEST_CASE("taylor in long double reaches below 1e-17 on the free top", "[taylor]") {
    // At t = 20 (along the way Boost's long double elliptic functions themselves err by up to
    // 2e-17, at t = 11, where Taylor and DOP853 in long double agree to 9e-19).
    using T = long double;
    const std::array<T, 3> w0 = {1, T(0.1L), T(0.5L)};
    const free_top_exact<T> exact({1, 2, 3}, w0);
    taylor<T> m;
    m.rtol = m.atol = 2e-19L; // eps(long double) = 1.08e-19
    Eigen::Matrix<T, 3, 1> y(w0[0], w0[1], w0[2]);
    REQUIRE(integrate(ROTGEN_GENERATED_TAYLOR_SYSTEM(free_top, T), m, T(0), y, T(20)).code ==
            status::ok);
    const auto e = exact(T(20));
    T error = 0;
    for (int i = 0; i < 3; ++i)
        error = std::max(error, std::abs(y[i] - e[static_cast<std::size_t>(i)]));
    // observed: 1.1e-18
    CHECK(error < 1e-17L);
}

TEST_CASE("taylor agrees with DOP853 on the heavy top and keeps its invariants", "[taylor]") {
    using vec = Eigen::Matrix<double, 6, 1>;
    const vec y0 = (vec() << 0.1, 0.5, 0.2, 0.3, 0.1, 10.0).finished();
    const double t_end = 10;
    const heavy_top::params<double> p;
    const auto sys = ROTGEN_GENERATED_TAYLOR_SYSTEM(heavy_top, double);
    taylor<double> m;
    m.rtol = m.atol = 1e-14;
    dop853<double> ref;
    ref.rtol = ref.atol = 1e-14;
    double e_drift = 0, pphi_drift = 0, ppsi_drift = 0;
    double mom0[3];
    heavy_top::momenta(y0.data(), mom0, p);
    const double e0 = heavy_top::energy(y0.data(), p);
    std::vector<double> times;
    for (int i = 1; i <= 200; ++i)
        times.push_back(t_end * i / 200);
    vec y = y0;
    const auto res = integrate(sys, m, 0.0, y, times, [&](double, const vec& s) {
        double mom[3];
        heavy_top::momenta(s.data(), mom, p);
        e_drift = std::max(e_drift, std::abs(heavy_top::energy(s.data(), p) - e0) / std::abs(e0));
        pphi_drift = std::max(pphi_drift, std::abs(mom[0] - mom0[0]) / std::abs(mom0[2]));
        ppsi_drift = std::max(ppsi_drift, std::abs(mom[2] - mom0[2]) / std::abs(mom0[2]));
    });
    REQUIRE(res.code == status::ok);
    vec y_ref = y0;
    REQUIRE(
        integrate(ROTGEN_GENERATED_SYSTEM_RHS(heavy_top, double), ref, 0.0, y_ref, t_end).code ==
        status::ok);
    // observed: |y - y_ref| 8.5e-13 (psi reaches 100 rad; DOP853's own error: against DOP853 in
    // long double at 2e-18, Taylor errs by 3e-14 at t = 20, DOP853 by 1.2e-12); drifts over
    // 200 samples 6.5e-16 (energy, relative), 5.2e-16 (p_phi), 3.5e-16 (p_psi, relative to p_psi)
    CHECK((y - y_ref).cwiseAbs().maxCoeff() < 2e-12);
    CHECK(e_drift < 5e-15);
    CHECK(pphi_drift < 5e-15);
    CHECK(ppsi_drift < 3e-15);
}

TEST_CASE("taylor chooses a higher order, not more steps, for a tighter tolerance", "[taylor]") {
    // Jorba-Zou's order ceil(-ln(eps)/2 + 1), and a step ~ rho/e^2 that barely depends on the
    // tolerance: observed (free top, t = 0..20) 1e-8: order 11, 45 steps; 1e-14: order 18,
    // 44 steps
    const auto loose = run_free_top<double>(1e-8, 20.0), tight = run_free_top<double>(1e-14, 20.0);
    CHECK(taylor<double>::order_for(1e-8) == 11);
    CHECK(taylor<double>::order_for(1e-14) == 18);
    CHECK(loose.steps > 40);
    CHECK(tight.steps <= loose.steps);
}

// Kahan's compensation of the state from step to step and the steps' compensated sum for the time
// (steppers/taylor.hpp, integrate/self_stepping.hpp): without either the rounding of the state or
// of t accumulates over the steps and sets the error floor. The final states (samples would also
// measure the dense output's truncation), with the orders of the tolerances as straight-line code.
TEST_CASE("taylor keeps the rounding of the state and of the time from accumulating", "[taylor]") {
    using vec = Eigen::Matrix<double, 6, 1>;
    using lvec = Eigen::Matrix<long double, 6, 1>;
    const vec y0 = (vec() << 0.1, 0.5, 0.2, 0.3, 0.1, 10.0).finished();
    taylor<long double> fine;
    fine.rtol = fine.atol = 2e-19L;
    lvec ref = y0.cast<long double>();
    REQUIRE(
        integrate(ROTGEN_GENERATED_TAYLOR_SYSTEM(heavy_top, long double), fine, 0.0L, ref, 10.0L)
            .ok());
    taylor<double> m;
    m.rtol = m.atol = 1e-15; // order 19
    vec y = y0;
    REQUIRE(integrate(ROTGEN_GENERATED_TAYLOR_SYSTEM_ORDERS(heavy_top, double, 19), m, 0.0, y, 10.0)
                .ok());
    double heavy = 0;
    for (Eigen::Index i = 0; i < 6; ++i)
        heavy = std::max(heavy, double(std::abs(static_cast<long double>(y[i]) - ref[i])));
    // the free top, t = 0..100 (221 steps) at tol 1e-14 (order 18), against its exact solution
    const std::array<long double, 3> w0 = {1, 0.1L, 0.5L};
    const auto e = free_top_exact<long double>({1, 2, 3}, w0)(100.0L);
    m.rtol = m.atol = 1e-14;
    Eigen::Vector3d w(1, 0.1, 0.5);
    REQUIRE(integrate(ROTGEN_GENERATED_TAYLOR_SYSTEM_ORDERS(free_top, double, 18), m, 0.0, w, 100.0)
                .ok());
    double free = 0;
    for (Eigen::Index i = 0; i < 3; ++i)
        free = std::max(free, double(std::abs(w[i] - e[static_cast<std::size_t>(i)])));
    // observed: heavy top 4.5e-15 (86 steps, psi reaches 100 rad), free top 3.0e-15; without the
    // state's compensation 9.0e-14 and 1.4e-14, without the time's 1.9e-14 and 2.5e-16, without
    // both 7.6e-14 and 1.8e-14
    CHECK(heavy < 1e-14);
    CHECK(free < 1e-14);
}

// The free top's Taylor system with its size known at run time only (size(), no state_size).
struct free_top_sized_at_run_time {
    free_top::params<double> p;
    std::size_t size() const { return 3; }
    void rhs(double t, const double* y, double* dydt) const { free_top::rhs(t, y, dydt, p); }
    std::size_t taylor_series() const { return free_top::taylor_series; }
    void taylor(double t, double* c, int order) const { free_top::taylor(t, c, order, p); }
};

// taylor_stepper loops over the components with the state's size as a constant when the system
// gives one (state_size) and as the run's otherwise: both take the same steps to the same bits,
// at the end and in the dense output between steps (the error against the exact solution at
// tol 1e-6: 1.4e-8 at t = 18.5).
TEST_CASE("taylor takes the same steps to the same bits with the size fixed or at run time",
          "[taylor]") {
    taylor<double> m;
    m.rtol = m.atol = 1e-6;
    std::vector<double> times;
    for (int i = 1; i <= 50; ++i)
        times.push_back(0.37 * i);
    const auto run = [&](const auto& sys, auto y) {
        std::vector<double> samples;
        const auto r = integrate(sys, m, 0.0, y, times, [&](double, const auto& v) {
            for (Eigen::Index i = 0; i < v.size(); ++i)
                samples.push_back(v[i]);
        });
        REQUIRE(r.ok());
        samples.push_back(double(r.stats.steps));
        return samples;
    };
    const auto fixed =
        run(ROTGEN_GENERATED_TAYLOR_SYSTEM(free_top, double), Eigen::Vector3d(1, 0.1, 0.5));
    Eigen::VectorXd y0(3);
    y0 << 1, 0.1, 0.5;
    const auto sized = run(free_top_sized_at_run_time{}, y0);
    REQUIRE(fixed.size() == 151); // 50 samples of 3 components, and the steps
    CHECK(sized == fixed);        // every bit (== on doubles)
    const auto e = free_top_exact<double>({1, 2, 3}, {1, 0.1, 0.5})(times.back());
    double error = 0;
    for (std::size_t i = 0; i < 3; ++i)
        error = std::max(error, std::abs(fixed[147 + i] - e[i]));
    CHECK(error < 1e-7); // observed 1.4e-8
}

// The step rule's one logarithm (taylor<T>::step_rule::max_ln_ratio): the bounds on log2 that
// pick which of max(ln(a) / (p - 1), ln(b) / p) to compute hold, and the answer has the bits of
// computing both, over quotients from 1e-300 to 1e300 and near ties, where it must take both.
TEST_CASE("taylor's step rule takes one logarithm with the bits of two", "[taylor]") {
    std::uint64_t state = 12345;
    const auto uniform = [&state] { // xorshift64*: a fixed, portable sequence in [0, 1)
        state ^= state >> 12, state ^= state << 25, state ^= state >> 27;
        return double((state * 2685821657736338717ULL) >> 11) * 0x1.0p-53;
    };
    double widest = 0;
    int differ = 0, ties = 0;
    for (int n = 0; n < 200000; ++n) {
        const double a = std::pow(10.0, 600 * uniform() - 300);
        const double lo = detail::log2_below(a), gap = std::log2(a) - lo;
        widest = std::max(widest, gap);
        if (!(gap >= -1e-12 && gap <= detail::log2_width)) ++differ;
        const int j = 2 + int(18 * uniform()), k = j + 1;
        // b near the tie ln(a) / j = ln(b) / k one time in two
        const double b = n % 2 ? std::pow(10.0, 600 * uniform() - 300)
                               : std::exp(std::log(a) * k / j * (1 + 1e-4 * (uniform() - 0.5)));
        if (!std::isnormal(b)) continue;
        const taylor<double>::step_rule rule(k);
        const double two = std::max(rule.ln(a) * rule.inv_p1, rule.ln(b) * rule.inv_p);
        const double one = rule.max_ln_ratio(a, b);
        if (std::memcmp(&one, &two, sizeof one) != 0) ++differ;
        ties += n % 2 == 0;
    }
    // observed: the bound's largest gap 0.086071 (log2(1/ln 2) - (1/ln 2 - 1)); no difference
    CHECK(widest > 0.0860);
    CHECK(widest <= detail::log2_width);
    CHECK(ties > 90000);
    CHECK(differ == 0);
}

// The step's exponential (detail::exp_step): within 1.7e-7 of exp over the range of its
// polynomial, bit for bit libm's beyond it (the steps of a series that ends or of a blow-up).
TEST_CASE("taylor's step exponential is within 1.7e-7 of exp and exp itself beyond", "[taylor]") {
    double worst = 0;
    for (int n = -200000; n <= 200000; ++n) {
        const double x = 700.0 * n / 200000;
        worst = std::max(worst, std::abs(detail::exp_step(x) / std::exp(x) - 1));
    }
    CHECK(worst > 1e-7); // observed 1.61e-7: the polynomial's error, not the last bit's
    CHECK(worst < 1.7e-7);
    for (const double x : {-710.0, -745.5, -800.0, 709.0, 710.0, 1e6, -1e6})
        CHECK(detail::exp_step(x) == std::exp(x));
    CHECK(detail::exp_step(-std::numeric_limits<double>::infinity()) == 0.0);
    CHECK(detail::exp_step(std::numeric_limits<double>::infinity()) ==
          std::numeric_limits<double>::infinity());
    CHECK(std::isnan(detail::exp_step(std::nan(""))));
}

// The step's logarithm (detail::ln_step): within 4e-8 of log for normal numbers, from the
// smallest to the largest.
TEST_CASE("taylor's step logarithm is within 4e-8 of log", "[taylor]") {
    double worst = 0;
    for (int n = -200000; n <= 200000; ++n) {
        const double x = std::pow(10.0, 307.5 * n / 200000);
        worst = std::max(worst, std::abs(detail::ln_step(x) - std::log(x)));
    }
    for (const double x : {std::numeric_limits<double>::min(), std::numeric_limits<double>::max(),
                           1.0, 2.0, 1.5, std::nextafter(2.0, 1.0)})
        worst = std::max(worst, std::abs(detail::ln_step(x) - std::log(x)));
    CHECK(worst > 3e-8); // observed 3.9e-8: the polynomial's error (5.6e-8 in log2), not rounding
    CHECK(worst < 4e-8);
}

// The sums of the step's series (detail::series_sums): Estrin's scheme for the orders 2 .. 16 and
// split Horner above, each within a few roundings of the sum in long double, for any number of
// components, and the same bits for a component whichever block it falls in.
TEST_CASE("taylor's series sums are within a few roundings at every order", "[taylor]") {
    std::uint64_t state = 777;
    const auto uniform = [&state] { // xorshift64*
        state ^= state >> 12, state ^= state << 25, state ^= state >> 27;
        return double((state * 2685821657736338717ULL) >> 11) * 0x1.0p-53;
    };
    double worst = 0;
    int differ = 0;
    for (int p = 2; p <= 40; ++p)
        for (int trial = 0; trial < 50; ++trial) {
            // coefficients falling as the step's do (h about a seventh of the radius), signs mixed
            std::vector<double> d(static_cast<std::size_t>(6 * p));
            for (int m = 0; m < p; ++m)
                for (int i = 0; i < 6; ++i)
                    d[static_cast<std::size_t>(i * p + m)] =
                        (uniform() - 0.5) * std::pow(7.0, -m) * (i + 1);
            const double h = 0.5 + uniform();
            const detail::series_view<double> at{d.data(), 1, std::size_t(p)};
            double six[6], each[6];
            detail::series_sums<6>(p, h, 6, at, six);
            detail::series_sums<-1>(p, h, 6, at, each); // a block of 4 and two single ones
            for (std::size_t i = 0; i < 6; ++i) {
                long double exact = 0, size = 0;
                for (int m = p - 1; m >= 0; --m)
                    exact = exact * h + at(m, i), size = size * h + std::abs(at(m, i));
                worst = std::max(worst, double(std::abs(six[i] - exact) / size) / 0x1.0p-53);
                differ += std::memcmp(&six[i], &each[i], sizeof(double)) != 0;
            }
        }
    // in units of the last place (2^-53) of sum |d(m)| h^m
    CHECK(worst < 4); // observed 3.1
    CHECK(differ == 0);
}
