// rotgen bench — the structure-exploiting methods in the driver, through the runtime code that
// `rotgen simulate` runs them with (no second implementation):
//   split2, split4, split6   steppers/splitting.hpp on the variant's body form (quaternion, omega)
//                            seen as a split system (split_system.hpp, body_split_system: the
//                            torque is I omega_dot at omega = 0), with the principal moments of
//                            the plan's `moments` line; fixed steps of the run's STEP, or steps
//                            under error control at rtol = atol = TOL (split_doubling.hpp), as
//                            generator/run/split_run.cpp runs a scene that gives step or rtol
//   taylor                   steppers/taylor.hpp on the variant's kernels and its generated Taylor
//                            coefficients (V::taylor, V::taylor_series), rtol = atol = TOL
// Their final states go through the variant's common(), like every other row's.
#pragma once

#include "run_record.hpp"
#include "runners.hpp"

#include <split_system.hpp>
#include <steppers/split_doubling.hpp>
#include <steppers/splitting.hpp>
#include <steppers/taylor.hpp>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>

namespace rotgen::bench {

// The variant's kernels with its Taylor coefficients (taylor_system.hpp's concept).
template <class V, class T> struct variant_taylor_system : variant_system<V, T> {
    std::size_t taylor_series() const { return V::taylor_series; }
    void taylor(T t, T* c, int order) const { V::taylor(t, c, order, this->p); }
};

// The variant's body form (7 states) as a split system that owns it: the body is built first
// (base order), then the split view that refers to it; never copied.
template <class V> struct variant_body { variant_system<V, double> body; };
template <class V>
class variant_split_system : private variant_body<V>,
                             public body_split_system<variant_system<V, double>> {
  public:
    explicit variant_split_system(const std::array<double, 3>& moments)
        : variant_body<V>{{V::template parameters<double>()}},
          body_split_system<variant_system<V, double>>(this->body, moments) {}
    variant_split_system(const variant_split_system&) = delete;
    variant_split_system& operator=(const variant_split_system&) = delete;
};

template <class V, int Order> run_record run_split(const run_spec& spec, const driver_settings& s) {
    static_assert(V::state_size == 7, "the split methods run the body form with the quaternion");
    const auto sys = std::make_shared<const variant_split_system<V>>(s.moments);
    const auto initial = V::initial();
    Eigen::VectorXd y0(7);
    for (Eigen::Index i = 0; i < 7; ++i)
        y0[i] = static_cast<double>(initial[static_cast<std::size_t>(i)]);
    if (spec.step > 0) {
        split_method<double, Order> m;
        m.step = spec.step;
        m.max_steps = 100000000;
        return run_system<double>(sys, m, y0, spec, s);
    }
    split_controlled<double, Order> m(spec.tol, spec.tol);
    rotgen::calibrate(m, V::layout()); // as generator/run/split_run.cpp does
    m.max_steps = 100000000;
    return run_system<double>(sys, m, y0, spec, s);
}

// split2/4/6 and taylor, when Mask compiles the method; none otherwise.
template <class V, class T, unsigned Mask>
std::optional<run_record> run_split_taylor(const run_spec& spec, const driver_settings& s) {
    if constexpr ((Mask & taylor_bit) != 0)
        if (spec.method == "taylor") {
            using system = variant_taylor_system<V, T>;
            taylor<T> m;
            m.rtol = m.atol = T(spec.tol);
            rotgen::calibrate(m, V::layout());
            m.step = T(spec.step);
            m.max_steps = 100000000;
            return run_system<T>(
                std::make_shared<const system>(system{{V::template parameters<T>()}}), m,
                initial_state<V, T>(), spec, s);
        }
    if constexpr (std::is_same_v<T, double>) {
        if constexpr ((Mask & split2_bit) != 0)
            if (spec.method == "split2") return run_split<V, 2>(spec, s);
        if constexpr ((Mask & split4_bit) != 0)
            if (spec.method == "split4") return run_split<V, 4>(spec, s);
        if constexpr ((Mask & split6_bit) != 0)
            if (spec.method == "split6") return run_split<V, 6>(spec, s);
    }
    return std::nullopt;
}

} // namespace rotgen::bench
