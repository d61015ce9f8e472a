// rotgen bench — one configuration of the plan run: rotgen's integrators (those the variant's
// method masks compile) and the peers (peers.hpp) on the same kernels. rotgen's adaptive methods
// are calibrated as `rotgen simulate` calibrates them (step_control.hpp: calibrate() with the
// variant's error layout), so that a bench tolerance is simulate's rtol = atol = tol; the peers
// keep their own meaning of a tolerance.
#pragma once

#include "peers.hpp"
#include "run_record.hpp"
#include "runners.hpp"
#include "split_taylor.hpp"

#include <rotgen.hpp>

#include <cstddef>
#include <string>

namespace rotgen::bench {

template <class V, class T, unsigned Mask>
run_record run_rotgen(const run_spec& spec, const driver_settings& s) {
    const T tol = T(spec.tol), step = T(spec.step);
    const std::size_t budget = 100000000;
    (void)tol, (void)step, (void)budget;
    if constexpr ((Mask & rk4_bit) != 0)
        if (spec.method == "rk4") {
            rk4<T> m;
            m.step = step;
            m.max_steps = budget;
            return run_method<V, T>(m, spec, s);
        }
    if constexpr ((Mask & dopri5_bit) != 0)
        if (spec.method == "dopri5") {
            dopri5<T> m(tol, tol);
            rotgen::calibrate(m, V::layout()); // rtol as `rotgen simulate` means it
            m.max_steps = budget;
            return run_method<V, T>(m, spec, s);
        }
    if constexpr ((Mask & dop853_bit) != 0)
        if (spec.method == "dop853") {
            dop853<T> m(tol, tol);
            rotgen::calibrate(m, V::layout());
            m.fixed_step = step; // > 0: fixed steps, no error control
            m.max_steps = budget;
            return run_method<V, T>(m, spec, s);
        }
    if constexpr ((Mask & midpoint_bit) != 0)
        if (spec.method == "implicit_midpoint") {
            implicit_midpoint<T> m;
            m.step = step;
            m.max_steps = budget;
            return run_method<V, T>(m, spec, s);
        }
    if constexpr ((Mask & rodas4_bit) != 0)
        if (spec.method == "rodas4") {
            rodas4<T> m(tol, tol);
            rotgen::calibrate(m, V::layout());
            m.autonomous = s.autonomous;
            m.max_steps = budget;
            return run_method<V, T>(m, spec, s);
        }
    if (auto rec = run_split_taylor<V, T, Mask>(spec, s)) return *rec;
    run_record rec;
    rec.spec = spec;
    rec.status = "not_compiled";
    return rec;
}

template <class V> double odeint_initial_step(const run_spec& spec, const driver_settings& s) {
    // the starting step rotgen's own heuristic picks for this tolerance and order
    const variant_system<V, double> sys{V::template parameters<double>()};
    const auto y0 = initial_state<V, double>();
    auto f0 = y0;
    step_stats st;
    sys.rhs(s.t0, y0.data(), f0.data());
    return detail::initial_step(sys, s.t0, y0, f0, 1.0, s.t1 - s.t0, spec.tol, spec.tol,
                                spec.method == "rkf78" ? 8 : 5, st);
}

template <class V> run_record run_one(const run_spec& spec, const driver_settings& s) {
    if (spec.peer == "rotgen") {
        if (spec.scalar == "double") return run_rotgen<V, double, V::double_methods>(spec, s);
        if (spec.scalar == "float") return run_rotgen<V, float, V::float_methods>(spec, s);
        if (spec.scalar == "long_double")
            return run_rotgen<V, long double, V::long_double_methods>(spec, s);
    }
    if (spec.peer == "odeint" && spec.scalar == "double") {
        if constexpr ((V::peers & odeint_dopri5) != 0)
            if (spec.method == "dopri5")
                return run_odeint<V, odeint_dopri5>(spec, s.t0, s.t1,
                                                    odeint_initial_step<V>(spec, s), s.times);
        if constexpr ((V::peers & odeint_rkf78) != 0)
            if (spec.method == "rkf78")
                return run_odeint<V, odeint_rkf78>(
                    spec, s.t0, s.t1, spec.step > 0 ? 0.0 : odeint_initial_step<V>(spec, s),
                    s.times);
        if constexpr ((V::peers & odeint_rk4) != 0)
            if (spec.method == "rk4")
                return run_odeint<V, odeint_rk4>(spec, s.t0, s.t1, spec.step, s.times);
    }
    if constexpr ((V::peers & cvode_bit) != 0)
        if (spec.peer == "cvode" && spec.scalar == "double")
            return run_cvode<V>(spec, s.t0, s.times);
    run_record rec;
    rec.spec = spec;
    rec.status = "not_compiled";
    return rec;
}

} // namespace rotgen::bench
