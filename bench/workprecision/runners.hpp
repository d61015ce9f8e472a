// rotgen bench — running one configuration: the runtime's system concept over a variant's
// kernels, one integration of it into a run_record whose `job` the driver times (timing.hpp), and
// the bits of rotgen's methods in the variants' method masks.
#pragma once

#include "run_record.hpp"

#include <rotgen.hpp>

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace rotgen::bench {

// The runtime's system concept over a variant's kernels.
template <class V, class T> struct variant_system {
    static constexpr std::size_t state_size = V::state_size;
    typename V::template params<T> p;
    void rhs(T t, const T* y, T* dydt) const { V::rhs(t, y, dydt, p); }
    void jacobian(T t, const T* y, T* J) const { V::jacobian(t, y, J, p); }
};

template <class V, class T> state_vector<T, variant_system<V, T>> initial_state() {
    const auto y0 = V::initial();
    state_vector<T, variant_system<V, T>> y;
    for (std::size_t i = 0; i < V::state_size; ++i)
        y[static_cast<Eigen::Index>(i)] = static_cast<T>(y0[i]);
    return y;
}

struct driver_settings {
    double t0 = 0, t1 = 1;
    double target = 0.02;
    int repeats = 5;
    bool autonomous = true;
    std::array<double, 3> moments{}; // the split methods' principal moments (split_taylor.hpp)
    std::vector<double> times;       // the scene's sample times, t0 .. t1: where runs are timed
                                     // and measured
};

// The states at `times` of one run of `m` on `sys` from y0 (the reference's), as `rotgen simulate`
// samples a scene; empty when the run fails.
template <class T, class System, class Method, class Vector>
std::vector<std::vector<long double>> sampled_states(const System& sys, const Method& m,
                                                     const Vector& y0,
                                                     const std::vector<double>& times) {
    const std::vector<T> at(times.begin(), times.end());
    sample_buffer<T> out(at.size(), std::size_t(y0.size()));
    Vector y = y0;
    const auto r = integrate(sys, m, at.front(), y, at, [&](T, const Vector& x) { out.put(x); });
    return r.ok() ? out.rows() : std::vector<std::vector<long double>>{};
}

// One configuration: `sys` (shared with the timed job) integrated by `m` from y0 to the scene's
// samples, as `rotgen simulate` runs it (dense output between the same steps), once now (the
// samples, the final state, the counters) and again each time the job is timed.
template <class T, class System, class Method, class Vector>
run_record run_system(std::shared_ptr<const System> sys, const Method& m, const Vector& y0,
                      const run_spec& spec, const driver_settings& s) {
    struct state {
        std::shared_ptr<const System> sys;
        Method method;
        Vector y0, y;
        std::vector<T> at;
        sample_buffer<T> samples;
        integration_result<T> r;
    };
    const auto st = std::make_shared<state>(
        state{std::move(sys), m, y0, y0, std::vector<T>(s.times.begin(), s.times.end()),
              sample_buffer<T>(s.times.size(), std::size_t(y0.size())), integration_result<T>{}});
    // one integration from the initial state (the same code runs untimed and timed)
    auto once = [st]() -> double {
        st->y = st->y0;
        st->samples.restart();
        st->r = integrate(*st->sys, st->method, st->at.front(), st->y, st->at,
                          [&kept = st->samples](T, const Vector& x) { kept.put(x); });
        return static_cast<double>(st->y[0]);
    };
    run_record rec;
    rec.spec = spec;
    once();
    rec.rhs_evals = st->r.stats.rhs_evals;
    rec.jac_evals = st->r.stats.jac_evals;
    rec.steps = st->r.stats.steps;
    for (Eigen::Index i = 0; i < st->y.size(); ++i)
        rec.y.push_back(static_cast<long double>(st->y[i]));
    if (!st->r.ok()) {
        rec.status = status_name(st->r.code);
        return rec;
    }
    rec.job.once = once;
    rec.samples = st->samples.rows();
    return rec;
}

// A method on the variant's kernels with its parameters.
template <class V, class T, class Method>
run_record run_method(const Method& m, const run_spec& spec, const driver_settings& s) {
    using system = variant_system<V, T>;
    return run_system<T>(std::make_shared<const system>(system{V::template parameters<T>()}), m,
                         initial_state<V, T>(), spec, s);
}

// rotgen's methods, one bit each.
enum method_bit : unsigned {
    rk4_bit = 1,
    dopri5_bit = 2,
    dop853_bit = 4,
    midpoint_bit = 8,
    rodas4_bit = 16,
    split2_bit = 32, // split_taylor.hpp
    split4_bit = 64,
    split6_bit = 128,
    taylor_bit = 256
};
inline constexpr unsigned cvode_bit = 8; // in V::peers, beside the odeint_method bits

} // namespace rotgen::bench
