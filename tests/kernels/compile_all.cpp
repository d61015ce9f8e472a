// Compiled by the ctest tests emit_compile_<compiler>_<scalar> with -Wall -Wextra -Wpedantic
// -Werror: every generated header, every function, instantiated for one scalar type.
#if defined(ROTGEN_SCALAR_eigen_array)
#include <Eigen/Core>
using scalar = Eigen::Array<double, 4, 1>;
#elif defined(ROTGEN_SCALAR_float)
using scalar = float;
#elif defined(ROTGEN_SCALAR_double)
using scalar = double;
#elif defined(ROTGEN_SCALAR_long_double)
using scalar = long double;
#else
#error "define ROTGEN_SCALAR_<float|double|long_double|eigen_array>"
#endif

#include "units.hpp"

template <class T> struct buffers {
    T y[7], f[7], J[49], out[9];
    buffers() {
        for (auto& v : y)
            v = T(0.5);
    }
};

#define ROTGEN_USE_COMMON(u)                                                                       \
    {                                                                                              \
        namespace ns = rotgen::models::u;                                                          \
        const ns::params<scalar> p{};                                                              \
        ns::rhs(scalar(0.25), b.y, b.f, p);                                                        \
        ns::jacobian(scalar(0.25), b.y, b.J, p);                                                   \
        ns::rhs_and_jacobian(scalar(0.25), b.y, b.f, b.J, p);                                      \
        b.out[0] = ns::energy(b.y, p);                                                             \
        ns::momenta(b.y, b.out, p);                                                                \
        scalar c[ns::taylor_series * 4];                                                           \
        for (auto& v : c)                                                                          \
            v = scalar(0.5);                                                                       \
        ns::taylor(scalar(0.25), c, 3, p);
#define ROTGEN_USE_FULL(u)                                                                         \
    ROTGEN_USE_COMMON(u)                                                                           \
    ns::omega(b.y, b.out, p);                                                                      \
    ns::rotation(b.y, b.out, p);                                                                   \
    ns::mass_matrix(b.y, b.out, p);                                                                \
    }
#define ROTGEN_USE_BODY(u)                                                                         \
    ROTGEN_USE_COMMON(u)                                                                           \
    ns::omega(b.y, b.out, p);                                                                      \
    ns::rotation(b.y, b.out, p);                                                                   \
    ns::mass_matrix(b.y, b.out, p);                                                                \
    }
#define ROTGEN_USE_BODY_OMEGA(u)                                                                   \
    ROTGEN_USE_COMMON(u)                                                                           \
    ns::omega(b.y, b.out, p);                                                                      \
    ns::mass_matrix(b.y, b.out, p);                                                                \
    }
#define ROTGEN_USE_REDUCED(u)                                                                      \
    ROTGEN_USE_COMMON(u)                                                                           \
    ns::ignored_rates(b.y, b.out, p);                                                              \
    }
// The sensitivity units (emit --sensitivities): rhs, jacobian, parameter_jacobian and
// variational_rhs, given params<T> and prepared<T>.
#define ROTGEN_USE_SENSITIVITIES(u)                                                                \
    {                                                                                              \
        namespace ns = rotgen::models::u;                                                          \
        const ns::params<scalar> p{};                                                              \
        constexpr std::size_t w = ns::state_size + ns::sensitivity_count;                          \
        scalar S[ns::state_size * w], dS[ns::state_size * w],                                      \
            D[ns::state_size * ns::sensitivity_count];                                             \
        for (auto& v : S)                                                                          \
            v = scalar(0.5);                                                                       \
        ns::rhs(scalar(0.25), b.y, b.f, p);                                                        \
        ns::jacobian(scalar(0.25), b.y, b.J, p);                                                   \
        ns::parameter_jacobian(scalar(0.25), b.y, D, p);                                           \
        ns::variational_rhs(scalar(0.25), b.y, S, b.f, dS, p);                                     \
        ns::variational_rhs(scalar(0.25), b.y, S, b.f, dS, ns::prepare(p));                        \
        b.out[0] = dS[0] + D[0];                                                                   \
    }

void use_all(buffers<scalar>& b);
void use_all(buffers<scalar>& b) {
#if !defined(ROTGEN_SCALAR_eigen_array)
    ROTGEN_UNITS_LAGRANGIAN(ROTGEN_USE_FULL)
    ROTGEN_UNITS_HAMILTONIAN(ROTGEN_USE_FULL)
    ROTGEN_UNITS_REDUCED(ROTGEN_USE_REDUCED)
    ROTGEN_UNITS_BODY(ROTGEN_USE_BODY)
    ROTGEN_UNITS_BODY_OMEGA(ROTGEN_USE_BODY_OMEGA)
    ROTGEN_UNITS_SENSITIVITIES(ROTGEN_USE_SENSITIVITIES)
#else
    // Eigen's expression templates make every statement expensive to compile (all units: ~150 s,
    // 3.6 GB): every form of one model, plus the full tensor (rotgen_emit_tests runs those).
    ROTGEN_USE_FULL(heavy_top)
    ROTGEN_USE_FULL(heavy_top_solve)
    ROTGEN_USE_FULL(heavy_top_specialised)
    ROTGEN_USE_FULL(heavy_top_hamiltonian)
    ROTGEN_USE_REDUCED(heavy_top_reduced)
    ROTGEN_USE_BODY(heavy_top_body)
    ROTGEN_USE_BODY_OMEGA(free_asymmetric_top_body_omega)
    ROTGEN_USE_FULL(full_tensor_top_solve_specialised)
    ROTGEN_USE_SENSITIVITIES(heavy_top_hamiltonian_sens)
    ROTGEN_USE_SENSITIVITIES(full_tensor_top_body_sens)
#endif
}

#if !defined(ROTGEN_SCALAR_eigen_array)
// The quaternion helpers are for scalar types (they use floor and atan2).
void use_helpers(scalar* q, scalar* a);
void use_helpers(scalar* q, scalar* a) {
    rotgen::models::heavy_top_body::quaternion_from_angles(a, q);
    rotgen::models::heavy_top_body::angles_from_quaternion(q, a);
}
#endif
