// Does the generated code lose more accuracy than the data force? For bench/extremes/moments.sh.
// The checked-in kernels of the free asymmetric top (generated/free_asymmetric_top_body.hpp,
// free_asymmetric_top.hpp, free_asymmetric_top_hamiltonian.hpp) are evaluated in double and, on
// the same double inputs, in long double (11 more bits: the "exact" value). At 10,000 random states
// (angles uniform, theta in [0.3, pi - 0.3], rates, momenta and omega in [-2, 2]) the error of each
// component f_i of the right-hand side is compared with what the rounding of the inputs forces:
//   data bound   u (|f_i| + sum_j |df_i/dy_j| |y_j| + sum_k |df_i/dI_k| |I_k|)
//   state bound  u (|f_i| + sum_j |df_i/dy_j| |y_j|)           (moments exactly representable)
// u = 2^-53; df/dy from the generated analytic Jacobian, df/dI by central differences, both in long
// double. Printed per form: the largest ratio error / bound over states and components. A ratio of
// order 1 means the kernel loses no more than the inputs' rounding forces; a ratio growing like
// 1/epsilon means a cancellation the formula could have avoided.
//   rhs_rounding I1 I2 I3
#include "free_asymmetric_top.hpp"
#include "free_asymmetric_top_body.hpp"
#include "free_asymmetric_top_hamiltonian.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

using real = long double;

// A generated header's namespace as a type.
#define ROTGEN_FORM(name, ns)                                                                      \
    struct name {                                                                                  \
        static constexpr std::size_t state_size = rotgen::models::ns::state_size;                  \
        template <class T> using params = rotgen::models::ns::params<T>;                           \
        template <class T> static void rhs(T t, const T* y, T* f, const params<T>& p) {            \
            rotgen::models::ns::rhs(t, y, f, p);                                                   \
        }                                                                                          \
        template <class T> static void jacobian(T t, const T* y, T* J, const params<T>& p) {       \
            rotgen::models::ns::jacobian(t, y, J, p);                                              \
        }                                                                                          \
    };
ROTGEN_FORM(body_form, free_asymmetric_top_body)
ROTGEN_FORM(lagrangian_form, free_asymmetric_top)
ROTGEN_FORM(hamiltonian_form, free_asymmetric_top_hamiltonian)

template <class Form> struct measure {
    static constexpr std::size_t n = Form::state_size;

    // {max error / data bound, max error / state bound}
    static std::array<double, 2> run(const std::array<double, 3>& I, std::mt19937_64& rng) {
        std::uniform_real_distribution<double> angle(0, 6.283185307179586),
            polar(0.3, 2.8415926535897931), rate(-2, 2);
        typename Form::template params<double> pd;
        typename Form::template params<real> pl;
        pd.I1 = I[0], pd.I2 = I[1], pd.I3 = I[2];
        pl.I1 = I[0], pl.I2 = I[1], pl.I3 = I[2];
        const real u = std::ldexp(real(1), -53);
        std::array<double, 2> worst{0, 0};
        for (int sample = 0; sample < 10000; ++sample) {
            std::array<double, n> yd;
            for (std::size_t j = 0; j < n; ++j)
                yd[j] = n == 3 ? rate(rng) : j == 1 ? polar(rng) : j < 3 ? angle(rng) : rate(rng);
            std::array<real, n> yl, fl, up, down;
            std::array<double, n> fd;
            std::array<real, n * n> J;
            for (std::size_t j = 0; j < n; ++j)
                yl[j] = yd[j];
            Form::rhs(0.0, yd.data(), fd.data(), pd);
            Form::rhs(real(0), yl.data(), fl.data(), pl);
            Form::jacobian(real(0), yl.data(), J.data(), pl);
            std::array<real, n> state_sum{}, data_sum{};
            for (std::size_t i = 0; i < n; ++i) {
                state_sum[i] = std::abs(fl[i]);
                for (std::size_t j = 0; j < n; ++j)
                    state_sum[i] += std::abs(J[i * n + j] * yl[j]);
                data_sum[i] = state_sum[i];
            }
            for (int k = 0; k < 3; ++k) { // df/dI_k I_k by central differences
                auto pk = pl;
                real& Ik = k == 0 ? pk.I1 : k == 1 ? pk.I2 : pk.I3;
                const real h = real(1e-6) * Ik;
                const real I0 = Ik;
                Ik = I0 + h;
                Form::rhs(real(0), yl.data(), up.data(), pk);
                Ik = I0 - h;
                Form::rhs(real(0), yl.data(), down.data(), pk);
                for (std::size_t i = 0; i < n; ++i)
                    data_sum[i] += std::abs((up[i] - down[i]) / (2 * h) * I0);
            }
            for (std::size_t i = 0; i < n; ++i) {
                const real err = std::abs(real(fd[i]) - fl[i]);
                if (err == 0) continue;
                worst[0] = std::max(worst[0], double(err / (u * data_sum[i])));
                worst[1] = std::max(worst[1], double(err / (u * state_sum[i])));
            }
        }
        return worst;
    }
};

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: rhs_rounding I1 I2 I3\n");
        return 2;
    }
    const std::array<double, 3> I = {std::strtod(argv[1], nullptr), std::strtod(argv[2], nullptr),
                                     std::strtod(argv[3], nullptr)};
    std::mt19937_64 rng(20240601);
    const auto body = measure<body_form>::run(I, rng);
    const auto lagrangian = measure<lagrangian_form>::run(I, rng);
    const auto hamiltonian = measure<hamiltonian_form>::run(I, rng);
    std::printf("%.1f %.1f %.1f %.1f %.1f %.1f\n", body[0], body[1], lagrangian[0], lagrangian[1],
                hamiltonian[0], hamiltonian[1]);
}
