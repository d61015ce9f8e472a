/// \file
/// rotgen runtime — the "system" concept and adapters.
///
/// A system is any type S with
///   static constexpr std::size_t state_size;            // compile-time size, or instead
///   std::size_t size() const;                           // a run-time size
///   void rhs(T t, const T* y, T* dydt) const;           // y' = f(t, y)
/// and optionally
///   void jacobian(T t, const T* y, T* J) const;         // dense, row-major N×N, J_ij = ∂f_i/∂y_j
///   T energy(T t, const T* y) const;                    // an invariant to monitor (scene layer)
///
/// State vectors are Eigen column vectors `state_vector<T, S>`: fixed-size `Eigen::Matrix<T, N, 1>`
/// when S has `state_size`, `Eigen::Matrix<T, Eigen::Dynamic, 1>` when it has `size()`.
/// Implicit methods use the analytic Jacobian when S has one, otherwise forward differences.
///
/// Adapters:
///   lambda_system<T, N>        — a system from lambdas (tests, small problems):
///                                 make_system<T, N>(rhs) or make_system<T, N>(rhs, jacobian)
///   generated_system<T, N, …>  — wraps a generated model namespace (free functions taking
///                                 `const params<T>&`), built with ROTGEN_GENERATED_SYSTEM(ns, T).
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>

#include "result.hpp"

namespace rotgen {

// ---- detection ---------------------------------------------------------------------------------

namespace detail {
template <class S, class = void> struct has_static_size : std::false_type {};
template <class S>
struct has_static_size<S, std::void_t<decltype(S::state_size)>> : std::true_type {};

template <class S, class T, class = void> struct has_jacobian : std::false_type {};
template <class S, class T>
struct has_jacobian<S, T,
                    std::void_t<decltype(std::declval<const S&>().jacobian(
                        std::declval<T>(), std::declval<const T*>(), std::declval<T*>()))>>
    : std::true_type {};

template <class S, class T, class = void> struct has_energy : std::false_type {};
template <class S, class T>
struct has_energy<S, T,
                  std::void_t<decltype(std::declval<const S&>().energy(
                      std::declval<T>(), std::declval<const T*>()))>> : std::true_type {};

template <class T> struct identity { using type = T; };
template <class T> using identity_t = typename identity<T>::type; // blocks template deduction
} // namespace detail

/// True when the system provides an analytic Jacobian for scalar type T.
template <class S, class T>
inline constexpr bool has_jacobian_v = detail::has_jacobian<S, T>::value;
/// True when the system provides `T energy(T t, const T* y) const`.
template <class S, class T> inline constexpr bool has_energy_v = detail::has_energy<S, T>::value;

/// Eigen compile-time dimension of a system's state: N, or Eigen::Dynamic for run-time sizes.
template <class S> constexpr int state_dim() {
    if constexpr (detail::has_static_size<S>::value)
        return static_cast<int>(S::state_size);
    else
        return Eigen::Dynamic;
}

/// The state size when it is a compile-time constant, else 0.
template <class S> constexpr std::size_t static_state_size() {
    if constexpr (detail::has_static_size<S>::value)
        return S::state_size;
    else
        return 0;
}

/// The state vector of system S: `Eigen::Matrix<T, N, 1>` for a compile-time size N, a dynamic
/// Eigen vector for a run-time size.
template <class T, class S> using state_vector = Eigen::Matrix<T, state_dim<S>(), 1>;

/// Row-major so that `.data()` matches the row-major layout of `jacobian(t, y, J)`.
template <class T, class S>
using jacobian_matrix = Eigen::Matrix<T, state_dim<S>(), state_dim<S>(),
                                      (state_dim<S>() == 1 ? Eigen::ColMajor : Eigen::RowMajor)>;

/// Number of state components of a system object.
template <class S> std::size_t system_size(const S& sys) {
    if constexpr (detail::has_static_size<S>::value) {
        (void)sys;
        return S::state_size;
    } else {
        return sys.size();
    }
}

// ---- adapters ----------------------------------------------------------------------------------

/// Placeholder for "no such function" in the adapters below.
struct no_function {};

/// A system built from lambdas: rhs(t, y, dydt) and optionally jacobian(t, y, J).
template <class T, std::size_t N, class Rhs, class Jac = no_function> class lambda_system {
  public:
    static constexpr std::size_t state_size = N; ///< the state size N

    /// The system of the callables rhs(t, y, dydt) and, optionally, jac(t, y, J).
    explicit lambda_system(Rhs rhs, Jac jac = Jac{})
        : m_rhs(std::move(rhs)), m_jac(std::move(jac)) {}

    /// dy/dt = f(t, y) into dydt (N values).
    void rhs(T t, const T* y, T* dydt) const { m_rhs(t, y, dydt); }

    /// J = ∂f/∂y at (t, y), dense row-major N×N, into jac (only when a Jacobian was given).
    template <class J = Jac, std::enable_if_t<!std::is_same_v<J, no_function>, int> = 0>
    void jacobian(T t, const T* y, T* jac) const {
        m_jac(t, y, jac);
    }

  private:
    Rhs m_rhs;
    Jac m_jac;
};

/// A lambda_system of N states, scalar T, from rhs(t, y, dydt).
template <class T, std::size_t N, class Rhs> auto make_system(Rhs rhs) {
    return lambda_system<T, N, Rhs>(std::move(rhs));
}

/// A lambda_system of N states, scalar T, from rhs(t, y, dydt) and jac(t, y, J) (row-major).
template <class T, std::size_t N, class Rhs, class Jac> auto make_system(Rhs rhs, Jac jac) {
    return lambda_system<T, N, Rhs, Jac>(std::move(rhs), std::move(jac));
}

/// A generated model (namespace `ns` with `params<T>`, `state_size`, `rhs`, and optionally
/// `jacobian`, `energy`) as a system. The parameters are held by value and may be changed
/// through the public member `params` between integrations.
///   Rhs:    callable (T t, const T* y, T* dydt, const Params& p)
///   Jac:    callable (T t, const T* y, T* J, const Params& p)   or no_function
///   Energy: callable (const T* y, const Params& p) -> T         or no_function
template <class T, std::size_t N, class Params, class Rhs, class Jac = no_function,
          class Energy = no_function>
class generated_system {
  public:
    static constexpr std::size_t state_size = N; ///< the state size N (ns::state_size)
    Params params; ///< the model's parameters (params<T>), changeable between integrations

    /// The system of parameters p and the namespace's kernels (see the class comment).
    generated_system(Params p, Rhs rhs, Jac jac = Jac{}, Energy energy = Energy{})
        : params(std::move(p)), m_rhs(std::move(rhs)), m_jac(std::move(jac)),
          m_energy(std::move(energy)) {}

    /// dy/dt = f(t, y) by the generated rhs with `params`.
    void rhs(T t, const T* y, T* dydt) const { m_rhs(t, y, dydt, params); }

    /// J = ∂f/∂y by the generated jacobian (dense row-major N×N), when one was given.
    template <class J = Jac, std::enable_if_t<!std::is_same_v<J, no_function>, int> = 0>
    void jacobian(T t, const T* y, T* jac) const {
        m_jac(t, y, jac, params);
    }

    /// The generated energy at the state y (t unused), when one was given.
    template <class E = Energy, std::enable_if_t<!std::is_same_v<E, no_function>, int> = 0>
    T energy(T /*t*/, const T* y) const {
        return m_energy(y, params);
    }

  private:
    Rhs m_rhs;
    Jac m_jac;
    Energy m_energy;
};

/// A generated_system of N states, scalar T, from parameters and the namespace's kernels (the
/// ROTGEN_GENERATED_SYSTEM macros call it).
template <class T, std::size_t N, class Params, class Rhs, class Jac = no_function,
          class Energy = no_function>
auto make_generated_system(Params p, Rhs rhs, Jac jac = Jac{}, Energy energy = Energy{}) {
    return generated_system<T, N, Params, Rhs, Jac, Energy>(std::move(p), std::move(rhs),
                                                            std::move(jac), std::move(energy));
}

} // namespace rotgen

/// Wraps a generated model namespace `ns` into a system with default parameters: rhs only.
/// The lambdas forward to the namespace's function templates so that the compiler can inline the
/// kernels.
///
///     auto sys = ROTGEN_GENERATED_SYSTEM(heavy_top, double);   // rhs + jacobian
///     sys.params.M = 2.0;
#define ROTGEN_GENERATED_SYSTEM_RHS(ns, T)                                                         \
    ::rotgen::make_generated_system<T, ns::state_size>(                                            \
        ns::params<T>{},                                                                           \
        [](T t_, const T* y_, T* d_, const ns::params<T>& p_) { ns::rhs<T>(t_, y_, d_, p_); })

/// As ROTGEN_GENERATED_SYSTEM_RHS, with ns::jacobian (implicit methods use it).
#define ROTGEN_GENERATED_SYSTEM(ns, T)                                                             \
    ::rotgen::make_generated_system<T, ns::state_size>(                                            \
        ns::params<T>{},                                                                           \
        [](T t_, const T* y_, T* d_, const ns::params<T>& p_) { ns::rhs<T>(t_, y_, d_, p_); },     \
        [](T t_, const T* y_, T* j_, const ns::params<T>& p_) {                                    \
            ns::jacobian<T>(t_, y_, j_, p_);                                                       \
        })

/// As ROTGEN_GENERATED_SYSTEM, with ns::energy as the system's energy(t, y) (an invariant to
/// monitor).
#define ROTGEN_GENERATED_SYSTEM_WITH_ENERGY(ns, T)                                                 \
    ::rotgen::make_generated_system<T, ns::state_size>(                                            \
        ns::params<T>{},                                                                           \
        [](T t_, const T* y_, T* d_, const ns::params<T>& p_) { ns::rhs<T>(t_, y_, d_, p_); },     \
        [](T t_, const T* y_, T* j_, const ns::params<T>& p_) {                                    \
            ns::jacobian<T>(t_, y_, j_, p_);                                                       \
        },                                                                                         \
        [](const T* y_, const ns::params<T>& p_) { return ns::energy<T>(y_, p_); })
