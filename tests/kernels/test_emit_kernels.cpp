// Generated kernels of every shipped model, in every form: the analytic Jacobian against central
// finite differences (values and sparsity pattern), rhs_and_jacobian against rhs and jacobian,
// double against long double, specialised against runtime parameters.
#include "kernels.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace rotgen_test;

namespace {

// d f / d y_k by central differences with one Richardson step (error O(h^4)).
std::vector<double> finite_difference_jacobian(const kernel& k, double t,
                                               const std::vector<double>& y) {
    const std::size_t n = k.n;
    std::vector<double> J(n * n), fp(n), fm(n);
    for (std::size_t c = 0; c < n; ++c) {
        const auto central = [&](double h) {
            std::vector<double> yp = y, ym = y;
            yp[c] += h;
            ym[c] -= h;
            k.rhs(t, yp.data(), fp.data());
            k.rhs(t, ym.data(), fm.data());
            std::vector<double> d(n);
            for (std::size_t r = 0; r < n; ++r)
                d[r] = (fp[r] - fm[r]) / (2 * h);
            return d;
        };
        const double h = 1e-3 * std::max(1.0, std::abs(y[c]));
        const std::vector<double> d1 = central(h), d2 = central(h / 2);
        for (std::size_t r = 0; r < n; ++r)
            J[r * n + c] = (4 * d2[r] - d1[r]) / 3;
    }
    return J;
}

} // namespace

TEST_CASE("the analytic Jacobian matches finite differences, entry and pattern",
          "[emit][jacobian]") {
    for (const kernel& k_default : kernels()) {
        // Parameters drawn at random too: an entry may vanish at particular values (the default
        // free asymmetric top has I3 = I1 + I2) without being structurally zero.
        std::mt19937 rng(20240601);
        std::uniform_real_distribution<double> parameter(0.5, 2.0);
        std::vector<double> values;
        for (std::size_t i = 0; i < k_default.parameter_names.size(); ++i)
            values.push_back(parameter(rng));
        const kernel k = k_default.with_parameters(values);
        INFO("unit " << k.unit);
        const std::size_t n = k.n;
        std::vector<double> max_fd(n * n, 0), max_analytic(n * n, 0);
        double worst = 0;
        for (int trial = 0; trial < 40; ++trial) {
            const std::vector<double> y = random_state(k, rng);
            const double t = 0.37 * trial;
            std::vector<double> J(n * n);
            k.jacobian(t, y.data(), J.data());
            const std::vector<double> fd = finite_difference_jacobian(k, t, y);
            double row_scale = 1;
            for (double v : J)
                row_scale = std::max(row_scale, std::abs(v));
            for (std::size_t i = 0; i < n * n; ++i) {
                const double err = std::abs(J[i] - fd[i]) / std::max(1.0, std::abs(J[i]));
                worst = std::max(worst, err);
                max_fd[i] = std::max(max_fd[i], std::abs(fd[i]) / row_scale);
                max_analytic[i] = std::max(max_analytic[i], std::abs(J[i]));
                if (err > 1e-7) {
                    INFO("entry (" << i / n << ", " << i % n << ") analytic " << J[i] << " fd "
                                   << fd[i]);
                    CHECK(err <= 1e-7);
                }
            }
        }
        INFO("worst relative error " << worst);
        CHECK(worst <= 1e-7);
        // Structural zeros: exactly zero analytically and zero (to rounding) by differences; and
        // every entry the pattern calls non-zero is non-zero somewhere.
        for (std::size_t i = 0; i < n * n; ++i) {
            INFO("entry (" << i / n << ", " << i % n << ") pattern " << int(k.pattern[i])
                           << " max |J| " << max_analytic[i] << " max |fd| " << max_fd[i]);
            if (k.pattern[i] == 0) {
                CHECK(max_analytic[i] == 0);
                CHECK(max_fd[i] <= 1e-9);
            } else {
                CHECK(max_fd[i] > 1e-9);
            }
        }
    }
}

TEST_CASE("rhs_and_jacobian gives what rhs and jacobian give", "[emit]") {
    for (const kernel& k : kernels()) {
        INFO("unit " << k.unit);
        std::mt19937 rng(7);
        for (int trial = 0; trial < 10; ++trial) {
            const std::vector<double> y = random_state(k, rng);
            std::vector<double> f1(k.n), f2(k.n), J1(k.n * k.n), J2(k.n * k.n);
            k.rhs(0.5, y.data(), f1.data());
            k.jacobian(0.5, y.data(), J1.data());
            k.rhs_and_jacobian(0.5, y.data(), f2.data(), J2.data());
            for (std::size_t i = 0; i < k.n; ++i)
                CHECK(f2[i] == Approx(f1[i]).epsilon(1e-13).margin(1e-13));
            for (std::size_t i = 0; i < k.n * k.n; ++i)
                CHECK(J2[i] == Approx(J1[i]).epsilon(1e-12).margin(1e-12));
        }
    }
}

TEST_CASE("double and long double kernels agree to double precision", "[emit][scalar]") {
    for (const kernel& k : kernels()) {
        INFO("unit " << k.unit);
        std::mt19937 rng(11);
        for (int trial = 0; trial < 10; ++trial) {
            const std::vector<double> y = random_state(k, rng);
            std::vector<long double> yl(y.begin(), y.end()), fl(k.n);
            std::vector<double> f(k.n);
            k.rhs(1.25, y.data(), f.data());
            k.rhs_long(1.25L, yl.data(), fl.data());
            double scale = 1;
            for (double v : f)
                scale = std::max(scale, std::abs(v));
            for (std::size_t i = 0; i < k.n; ++i)
                CHECK(std::abs(f[i] - static_cast<double>(fl[i])) <= 1e-13 * scale);
        }
    }
}

TEST_CASE("specialised kernels equal runtime-parameter kernels at the defaults",
          "[emit][specialise]") {
    const std::vector<std::pair<std::string, std::string>> pairs{
        {"heavy_top_specialised", "heavy_top"},
        {"full_tensor_top_solve_specialised", "full_tensor_top_solve"},
        {"heavy_top_reduced_specialised", "heavy_top_reduced"}};
    for (const auto& [special, general] : pairs) {
        const kernel& a = find_kernel(special);
        const kernel& b = find_kernel(general);
        INFO(special << " vs " << general);
        REQUIRE(a.n == b.n);
        CHECK(a.parameter_names.size() < b.parameter_names.size());
        std::mt19937 rng(3);
        for (int trial = 0; trial < 10; ++trial) {
            const std::vector<double> y = random_state(b, rng);
            std::vector<double> fa(a.n), fb(b.n), Ja(a.n * a.n), Jb(b.n * b.n);
            a.rhs(0.1, y.data(), fa.data());
            b.rhs(0.1, y.data(), fb.data());
            a.jacobian(0.1, y.data(), Ja.data());
            b.jacobian(0.1, y.data(), Jb.data());
            for (std::size_t i = 0; i < a.n; ++i)
                CHECK(fa[i] == Approx(fb[i]).epsilon(1e-12).margin(1e-12));
            for (std::size_t i = 0; i < a.n * a.n; ++i)
                CHECK(Ja[i] == Approx(Jb[i]).epsilon(1e-11).margin(1e-11));
            CHECK(a.energy(y.data()) == Approx(b.energy(y.data())).epsilon(1e-13));
        }
    }
}

TEST_CASE("the reduced heavy top has two states and keeps its conserved momenta as parameters",
          "[emit][reduced]") {
    const kernel& k = find_kernel("heavy_top_reduced");
    CHECK(k.n == 2);
    CHECK(k.state_names == std::vector<std::string>{"theta", "p_theta"});
    CHECK(std::find(k.parameter_names.begin(), k.parameter_names.end(), "p_phi") !=
          k.parameter_names.end());
    CHECK(std::find(k.parameter_names.begin(), k.parameter_names.end(), "p_psi") !=
          k.parameter_names.end());
    // p_phi, p_psi stay runtime parameters even when everything else is folded in
    const kernel& s = find_kernel("heavy_top_reduced_specialised");
    CHECK(std::find(s.parameter_names.begin(), s.parameter_names.end(), "p_phi") !=
          s.parameter_names.end());
    CHECK(std::find(s.parameter_names.begin(), s.parameter_names.end(), "I1") ==
          s.parameter_names.end());
}
