// The Taylor coefficients for an order known when compiled (taylor_fixed<Order>, the recurrences
// unrolled and their sums added pairwise) against the loop of taylor(), for every order 1..20, on
// the state of the heavy top (products, a square, a quotient, sin and cos) and of the free top;
// and taylor_specialised's choice between them.
#include <catch2/catch.hpp>

#include "free_asymmetric_top_body_taylor.hpp"
#include "heavy_top_taylor.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace heavy_top = rotgen::models::heavy_top_taylor;
namespace free_top = rotgen::models::free_asymmetric_top_body_taylor;

namespace {

// The coefficients of every series through the state y, by the loop (order at run time).
template <class Model, std::size_t N>
std::vector<double> by_loop(const std::array<double, N>& y, int order) {
    const std::size_t m = static_cast<std::size_t>(order) + 1;
    std::vector<double> c(Model::taylor_series * m, 0.0);
    for (std::size_t i = 0; i < N; ++i)
        c[i * m] = y[i];
    Model::run_loop(c.data(), order);
    return c;
}

struct heavy_model {
    static constexpr std::size_t taylor_series = heavy_top::taylor_series;
    static void run_loop(double* c, int order) {
        heavy_top::taylor(0.0, c, order, heavy_top::params<double>{});
    }
    template <int P> static void run_fixed(double* c) {
        heavy_top::taylor_fixed<P>(0.0, c, heavy_top::params<double>{});
    }
};
struct free_model {
    static constexpr std::size_t taylor_series = free_top::taylor_series;
    static void run_loop(double* c, int order) {
        free_top::taylor(0.0, c, order, free_top::params<double>{});
    }
    template <int P> static void run_fixed(double* c) {
        free_top::taylor_fixed<P>(0.0, c, free_top::params<double>{});
    }
};

// max over the state's series and coefficients of |fixed - loop| / max(|loop| of that coefficient
// over the state, tiny): the two differ only in the order of the additions. (taylor_fixed computes
// a product that only a rate reads inside the rate, and leaves its series as scratch.)
template <class Model, int P, std::size_t N> double deviation(const std::array<double, N>& y) {
    const std::vector<double> loop = by_loop<Model>(y, P);
    std::vector<double> c(loop.size(), 0.0);
    const std::size_t m = P + 1;
    for (std::size_t i = 0; i < N; ++i)
        c[i * m] = y[i];
    Model::template run_fixed<P>(c.data());
    double worst = 0;
    for (std::size_t k = 0; k < m; ++k) {
        double scale = 1e-300;
        for (std::size_t s = 0; s < N; ++s)
            scale = std::max(scale, std::abs(loop[s * m + k]));
        for (std::size_t s = 0; s < N; ++s)
            worst = std::max(worst, std::abs(c[s * m + k] - loop[s * m + k]) / scale);
    }
    return worst;
}

template <class Model, std::size_t N, int... P>
double worst_over_orders(const std::array<double, N>& y, std::integer_sequence<int, P...>) {
    return std::max({deviation<Model, P + 1>(y)...});
}

} // namespace

TEST_CASE("taylor_fixed gives the loop's coefficients at every order 1 to 20", "[taylor]") {
    // heavy top: (phi, theta, psi, rates) of the nutation scene; free top: omega0 = (1, 0.1, 0.5)
    const std::array<double, 6> h{0.1, 0.5, 0.2, 0.3, 0.1, 10.0};
    const std::array<double, 3> f{1.0, 0.1, 0.5};
    const double heavy_dev =
        worst_over_orders<heavy_model>(h, std::make_integer_sequence<int, 20>{});
    const double free_dev = worst_over_orders<free_model>(f, std::make_integer_sequence<int, 20>{});
    // observed 2.2e-16 (heavy) and 2.2e-16 (free): rounding alone; a wrong index or term is O(1)
    CHECK(heavy_dev < 2e-15);
    CHECK(free_dev < 2e-15);
}

TEST_CASE("taylor_specialised runs taylor_fixed for its orders and the loop for others",
          "[taylor]") {
    const std::array<double, 6> y{0.1, 0.5, 0.2, 0.3, 0.1, 10.0};
    const auto run = [&](int order, auto call) {
        const std::size_t m = static_cast<std::size_t>(order) + 1;
        std::vector<double> c(heavy_top::taylor_series * m, 0.0);
        for (std::size_t i = 0; i < 6; ++i)
            c[i * m] = y[i];
        call(c.data());
        return c;
    };
    const heavy_top::params<double> p{};
    const auto loop15 = run(15, [&](double* c) { heavy_top::taylor(0.0, c, 15, p); });
    const auto fixed15 = run(15, [&](double* c) { heavy_top::taylor_fixed<15>(0.0, c, p); });
    const auto spec15 =
        run(15, [&](double* c) { heavy_top::taylor_specialised<11, 15>(0.0, c, 15, p); });
    const auto spec14 =
        run(14, [&](double* c) { heavy_top::taylor_specialised<11, 15>(0.0, c, 14, p); });
    const auto loop14 = run(14, [&](double* c) { heavy_top::taylor(0.0, c, 14, p); });
    CHECK(spec15 == fixed15);
    CHECK(spec14 == loop14);
    CHECK(fixed15 != loop15); // the pairwise sums round differently somewhere (not a copy)
}
