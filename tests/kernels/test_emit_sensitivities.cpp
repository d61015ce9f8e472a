// The sensitivity kernels of `rotgen emit --sensitivities` (the <unit>_sens headers of
// tests/kernels/CMakeLists.txt): parameter_jacobian against central finite differences of the
// emitted rhs in each parameter, variational_rhs against (d f/d y) S + [0 | d f/d p] assembled
// from the emitted jacobian and parameter_jacobian, and its dydt against rhs.
#include "kernels.hpp"
#include "units.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <type_traits>

using namespace rotgen_test;

namespace {

// One sensitivity unit, its parameters as a vector (parameter_names order).
struct sensitivity_kernel {
    std::string unit, model;
    std::size_t n = 0, k = 0;
    std::vector<std::string> parameter_names, keys;
    std::vector<double> defaults;
    std::function<void(const std::vector<double>&, double, const double*, double*)> rhs, jacobian,
        parameter_jacobian;
    std::function<void(const std::vector<double>&, double, const double*, const double*, double*,
                       double*)>
        variational_rhs;
};

// params<double> holds parameter_count doubles and nothing else: copied to and from a vector.
template <class P> std::vector<double> values_of(const P& p, std::size_t count) {
    static_assert(std::is_trivially_copyable<P>::value, "params<double> is plain data");
    std::vector<double> v(count);
    if (count) std::memcpy(v.data(), &p, count * sizeof(double));
    return v;
}

template <class P> P params_of(const std::vector<double>& v) {
    P p{};
    if (!v.empty()) std::memcpy(static_cast<void*>(&p), v.data(), v.size() * sizeof(double));
    return p;
}

#define ROTGEN_SENSITIVITY_KERNEL(u)                                                               \
    {                                                                                              \
        namespace ns = rotgen::models::u;                                                          \
        using P = ns::params<double>;                                                              \
        static_assert(sizeof(P) ==                                                                 \
                          sizeof(double) * (ns::parameter_count ? ns::parameter_count : 1),        \
                      "params<double> is parameter_count doubles");                                \
        sensitivity_kernel s;                                                                      \
        s.unit = #u;                                                                               \
        s.model = ns::model_name;                                                                  \
        s.n = ns::state_size;                                                                      \
        s.k = ns::sensitivity_count;                                                               \
        s.parameter_names.assign(ns::parameter_names.begin(), ns::parameter_names.end());          \
        s.keys.assign(ns::sensitivity_names.begin(), ns::sensitivity_names.end());                 \
        s.defaults = values_of(P{}, ns::parameter_count);                                          \
        s.rhs = [](const std::vector<double>& v, double t, const double* y, double* f) {           \
            ns::rhs(t, y, f, params_of<P>(v));                                                     \
        };                                                                                         \
        s.jacobian = [](const std::vector<double>& v, double t, const double* y, double* J) {      \
            ns::jacobian(t, y, J, params_of<P>(v));                                                \
        };                                                                                         \
        s.parameter_jacobian = [](const std::vector<double>& v, double t, const double* y,         \
                                  double* D) {                                                     \
            ns::parameter_jacobian(t, y, D, params_of<P>(v));                                      \
        };                                                                                         \
        s.variational_rhs = [](const std::vector<double>& v, double t, const double* y,            \
                               const double* S, double* f, double* dS) {                           \
            ns::variational_rhs(t, y, S, f, dS, ns::prepare(params_of<P>(v)));                     \
        };                                                                                         \
        r.push_back(s);                                                                            \
    }

std::vector<sensitivity_kernel> sensitivity_kernels() {
    std::vector<sensitivity_kernel> r;
    ROTGEN_UNITS_SENSITIVITIES(ROTGEN_SENSITIVITY_KERNEL)
    return r;
}

// The shipped unit with the same state layout: <unit> without _sens (and _folded).
const kernel& layout_of(const sensitivity_kernel& s) {
    std::string base = s.unit.substr(0, s.unit.size() - std::string("_sens").size());
    const std::string folded = "_folded";
    if (base.size() > folded.size() &&
        base.compare(base.size() - folded.size(), folded.size(), folded) == 0)
        base.resize(base.size() - folded.size());
    return find_kernel(base);
}

// The parameters at their defaults, each scaled by a random factor in [0.8, 1.25] (no special
// values such as I3 = I1 + I2).
std::vector<double> random_parameters(const sensitivity_kernel& s, std::mt19937& rng) {
    std::uniform_real_distribution<double> factor(0.8, 1.25);
    std::vector<double> v = s.defaults;
    for (double& x : v)
        x *= factor(rng);
    return v;
}

std::size_t index_of(const std::vector<std::string>& names, const std::string& name) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
}

// d f / d p_j by central differences of rhs with one Richardson step (error O(h^4)), row-major
// n x k.
std::vector<double> finite_difference_parameter_jacobian(const sensitivity_kernel& s,
                                                         const std::vector<double>& p, double t,
                                                         const std::vector<double>& y) {
    const std::size_t n = s.n, k = s.k;
    std::vector<double> D(n * k), fp(n), fm(n);
    for (std::size_t j = 0; j < k; ++j) {
        const std::size_t at = index_of(s.parameter_names, s.keys[j]);
        const auto central = [&](double h) {
            std::vector<double> pp = p, pm = p, d(n);
            pp[at] += h;
            pm[at] -= h;
            s.rhs(pp, t, y.data(), fp.data());
            s.rhs(pm, t, y.data(), fm.data());
            for (std::size_t i = 0; i < n; ++i)
                d[i] = (fp[i] - fm[i]) / (2 * h);
            return d;
        };
        const double h = 1e-3 * std::max(1.0, std::abs(p[at]));
        const std::vector<double> d1 = central(h), d2 = central(h / 2);
        for (std::size_t i = 0; i < n; ++i)
            D[i * k + j] = (4 * d2[i] - d1[i]) / 3;
    }
    return D;
}

} // namespace

TEST_CASE("the parameter Jacobian matches finite differences of rhs in each parameter",
          "[emit][sensitivities]") {
    // the worst |analytic - difference| / max(1, |analytic|) over 30 states and parameter sets,
    // by model, in any form; observed (g++ -O3, x86-64): heavy top 1.0e-11 (hamiltonian),
    // full-tensor top 8.8e-12 (hamiltonian), z-y-x satellite 3.2e-11 (lagrangian)
    const std::map<std::string, double> bound{
        {"heavy_top", 1e-10}, {"full_tensor_top", 9e-11}, {"satellite_zyx", 3e-10}};
    std::map<std::string, std::vector<std::string>> forms_seen;
    for (const sensitivity_kernel& s : sensitivity_kernels()) {
        INFO("unit " << s.unit);
        const kernel& layout = layout_of(s);
        REQUIRE(layout.n == s.n);
        std::mt19937 rng(20261128);
        double worst = 0;
        for (int trial = 0; trial < 30; ++trial) {
            const std::vector<double> p = random_parameters(s, rng);
            const std::vector<double> y = random_state(layout, rng);
            const double t = 0.29 * trial;
            std::vector<double> D(s.n * s.k);
            s.parameter_jacobian(p, t, y.data(), D.data());
            const std::vector<double> fd = finite_difference_parameter_jacobian(s, p, t, y);
            for (std::size_t i = 0; i < D.size(); ++i)
                worst = std::max(worst, std::abs(D[i] - fd[i]) / std::max(1.0, std::abs(D[i])));
        }
        CHECK(worst <= bound.at(s.model));
        forms_seen[s.model].push_back(s.unit);
    }
    // three models, each in five forms (lagrangian, solve, hamiltonian, body, reduced)
    REQUIRE(forms_seen.size() == 3);
    for (const auto& [model, units] : forms_seen)
        CHECK(units.size() >= 5);
}

TEST_CASE("variational_rhs is (d f/d y) S + [0 | d f/d p] and its dydt is rhs",
          "[emit][sensitivities]") {
    for (const sensitivity_kernel& s : sensitivity_kernels()) {
        INFO("unit " << s.unit);
        const kernel& layout = layout_of(s);
        const std::size_t n = s.n, k = s.k, w = n + k;
        std::mt19937 rng(20261129);
        std::uniform_real_distribution<double> entry(-1, 1);
        double worst_f = 0, worst_S = 0;
        for (int trial = 0; trial < 20; ++trial) {
            const std::vector<double> p = random_parameters(s, rng);
            const std::vector<double> y = random_state(layout, rng);
            const double t = 0.41 * trial;
            std::vector<double> S(n * w), f(n), dS(n * w), f_rhs(n), J(n * n), D(n * k);
            for (double& x : S)
                x = entry(rng);
            s.variational_rhs(p, t, y.data(), S.data(), f.data(), dS.data());
            s.rhs(p, t, y.data(), f_rhs.data());
            s.jacobian(p, t, y.data(), J.data());
            s.parameter_jacobian(p, t, y.data(), D.data());
            for (std::size_t i = 0; i < n; ++i) {
                worst_f = std::max(worst_f,
                                   std::abs(f[i] - f_rhs[i]) / std::max(1.0, std::abs(f_rhs[i])));
                for (std::size_t c = 0; c < w; ++c) {
                    double expected = c >= n ? D[i * k + (c - n)] : 0.0, scale = 1;
                    for (std::size_t m = 0; m < n; ++m) {
                        expected += J[i * n + m] * S[m * w + c];
                        scale += std::abs(J[i * n + m] * S[m * w + c]);
                    }
                    worst_S = std::max(worst_S, std::abs(dS[i * w + c] - expected) / scale);
                }
            }
        }
        // dydt: variational_rhs lowers f together with d f/d y and d f/d p, so its rounding may
        // differ from rhs's (as rhs_and_jacobian's does). Observed (g++ -O3, x86-64), worst over
        // the units: dydt 2.7e-15, dSdt 6.2e-15 relative (satellite_zyx_solve_sens)
        CHECK(worst_f <= 3e-14);
        CHECK(worst_S <= 6e-14);
    }
}
