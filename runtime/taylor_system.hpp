/// \file
/// rotgen runtime — a generated model with its Taylor coefficients as a system the Taylor method
/// (steppers/taylor.hpp) integrates: the header emitted with `--outputs rhs,taylor`.
///
///   auto sys = ROTGEN_GENERATED_TAYLOR_SYSTEM(heavy_top, double);
///   sys.params.M = 2.0;
///   rotgen::taylor<double> method;  method.rtol = method.atol = 1e-12;
///   rotgen::integrate(sys, method, t0, y, t_end);
#pragma once

#include <cstddef>
#include <utility>

namespace rotgen {

/// rhs(t, y, dydt, p) and taylor(t, c, order, p) of a generated namespace, with its parameters
/// held by value (the public member `params`, changeable between integrations).
template <class T, std::size_t N, class Params, class Rhs, class Taylor>
class generated_taylor_system {
  public:
    static constexpr std::size_t state_size = N; ///< the state size N (ns::state_size)
    Params params; ///< the model's parameters (params<T>), changeable between integrations

    /// The system of parameters p, ns::taylor_series Taylor series and the namespace's rhs and
    /// taylor.
    generated_taylor_system(Params p, std::size_t series, Rhs rhs, Taylor taylor)
        : params(std::move(p)), m_series(series), m_rhs(std::move(rhs)),
          m_taylor(std::move(taylor)) {}

    /// dy/dt = f(t, y) by the generated rhs with `params`.
    void rhs(T t, const T* y, T* dydt) const { m_rhs(t, y, dydt, params); }
    /// The number of Taylor series the generated taylor() expands (ns::taylor_series).
    std::size_t taylor_series() const { return m_series; }
    /// The Taylor coefficients up to `order` at t into c, by the generated taylor() (layout in
    /// steppers/taylor.hpp).
    void taylor(T t, T* c, int order) const { m_taylor(t, c, order, params); }

  private:
    std::size_t m_series;
    Rhs m_rhs;
    Taylor m_taylor;
};

/// A generated_taylor_system of N states, scalar T (ROTGEN_GENERATED_TAYLOR_SYSTEM calls it).
template <class T, std::size_t N, class Params, class Rhs, class Taylor>
auto make_generated_taylor_system(Params p, std::size_t series, Rhs rhs, Taylor taylor) {
    return generated_taylor_system<T, N, Params, Rhs, Taylor>(std::move(p), series, std::move(rhs),
                                                              std::move(taylor));
}

} // namespace rotgen

/// Wraps a generated namespace `ns` emitted with `--outputs rhs,taylor` into a
/// generated_taylor_system with default parameters (example in the file's comment).
#define ROTGEN_GENERATED_TAYLOR_SYSTEM(ns, T)                                                      \
    ::rotgen::make_generated_taylor_system<T, ns::state_size>(                                     \
        ns::params<T>{}, ns::taylor_series,                                                        \
        [](T t_, const T* y_, T* d_, const ns::params<T>& p_) { ns::rhs<T>(t_, y_, d_, p_); },     \
        [](T t_, T* c_, int o_, const ns::params<T>& p_) { ns::taylor<T>(t_, c_, o_, p_); })

/// The same with the orders given compiled as straight-line code (ns::taylor_specialised): the
/// orders the tolerances give, rotgen::taylor<T>::order_for(tol) (15 for 1e-12); others by the
/// loop.
///
///     auto sys = ROTGEN_GENERATED_TAYLOR_SYSTEM_ORDERS(heavy_top, double, 15);
#define ROTGEN_GENERATED_TAYLOR_SYSTEM_ORDERS(ns, T, ...)                                          \
    ::rotgen::make_generated_taylor_system<T, ns::state_size>(                                     \
        ns::params<T>{}, ns::taylor_series,                                                        \
        [](T t_, const T* y_, T* d_, const ns::params<T>& p_) { ns::rhs<T>(t_, y_, d_, p_); },     \
        [](T t_, T* c_, int o_, const ns::params<T>& p_) {                                         \
            ns::taylor_specialised<__VA_ARGS__>(t_, c_, o_, p_);                                   \
        })
