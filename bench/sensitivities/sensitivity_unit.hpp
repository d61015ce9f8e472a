// A unit of `rotgen emit --sensitivities` as a type (ROTGEN_SENSITIVITY_UNIT), and S(t_end) by
// rotgen's DOP853 on its variational_rhs: shared by bench/sensitivities/sensitivity_bench.cpp and
// tests/kernels/test_cvodes_sensitivities.cpp (with cvodes_route.hpp, the CVODES route).
#pragma once

#include <rotgen.hpp>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

// struct `type`: the kernels of namespace rotgen::models::u (double), its sizes n and k, and
// parameter_index(key): the position in params<double> of the key-th sensitivity parameter.
#define ROTGEN_SENSITIVITY_UNIT(type, u)                                                           \
    struct type {                                                                                  \
        using P = rotgen::models::u::params<double>;                                               \
        static constexpr std::size_t n = rotgen::models::u::state_size;                            \
        static constexpr std::size_t k = rotgen::models::u::sensitivity_count;                     \
        template <class... A> static void rhs(A&&... a) {                                          \
            rotgen::models::u::rhs(std::forward<A>(a)...);                                         \
        }                                                                                          \
        template <class... A> static void jacobian(A&&... a) {                                     \
            rotgen::models::u::jacobian(std::forward<A>(a)...);                                    \
        }                                                                                          \
        template <class... A> static void parameter_jacobian(A&&... a) {                           \
            rotgen::models::u::parameter_jacobian(std::forward<A>(a)...);                          \
        }                                                                                          \
        template <class... A> static void variational_rhs(A&&... a) {                              \
            rotgen::models::u::variational_rhs(std::forward<A>(a)...);                             \
        }                                                                                          \
        static auto prepare(const P& p) { return rotgen::models::u::prepare(p); }                  \
        static std::size_t parameter_index(std::size_t key) {                                      \
            const auto& names = rotgen::models::u::parameter_names;                                \
            const std::string want = rotgen::models::u::sensitivity_names[key];                    \
            for (std::size_t i = 0; i < names.size(); ++i)                                         \
                if (want == names[i]) return i;                                                    \
            return names.size();                                                                   \
        }                                                                                          \
    };

namespace sensitivity_routes {

// S(t_end), row-major n x (n + k) (S(0) = [I | 0]), by DOP853 at rtol, atol = rtol / 100 on
// variational_rhs (y and S in one kernel) from y0 with the default parameters; empty when the
// integration failed.
template <class U>
std::vector<double> variational(const std::vector<double>& y0, double t_end, double rtol) {
    constexpr std::size_t n = U::n, nk = U::n + U::k, size = n + n * nk;
    const auto prepared = U::prepare(typename U::P{});
    auto sys = rotgen::make_system<double, size>([&](double t, const double* z, double* dz) {
        U::variational_rhs(t, z, z + n, dz, dz + n, prepared);
    });
    rotgen::state_vector<double, decltype(sys)> z = decltype(z)::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        z[static_cast<Eigen::Index>(i)] = y0[i];
        z[static_cast<Eigen::Index>(n + i * nk + i)] = 1.0;
    }
    if (!rotgen::integrate(sys, rotgen::dop853<double>(rtol, rtol / 100), 0.0, z, t_end).ok())
        return {};
    return std::vector<double>(z.data() + n, z.data() + size);
}

} // namespace sensitivity_routes
