// rotgen bench — the work-precision driver: reads a plan, runs every configuration on the
// variants compiled into this translation unit, and writes one line per result.
//
// `rotgen bench` (generator/bench_command.cpp) generates the kernels of every variant (formulation
// x code generation), fills bench/workprecision/driver.cpp.in with them and with one `variant`
// struct each, compiles that translation unit once (-O3, cached), and runs it:
//     driver PLAN OUT
// A variant struct V provides (all static):
//     form                          the `form` column: "body", "lagrangian:solve+runtime", ...
//     state_size, params<T>, parameters<T>()   the kernels' parameter struct, filled with the
//                                   scene's values (and a reduced form's conserved momenta)
//     initial()                     std::array<long double, state_size>, the initial state
//     rhs(t, y, dydt, p), jacobian(t, y, J, p)   the generated kernels (row-major J)
//     energy(y, e) -> bool          the energy in long double, if the form gives it
//     momenta(y, out) -> int        the conserved momenta (cyclic coordinates), their count
//     common(y, c)                  the common representation (common_state.hpp)
//     double_methods, float_methods, long_double_methods, drift_methods   bit masks of rotgen's
//                                   methods (method_bit) the plan uses with each scalar type
//     peers                         bit mask: odeint_method bits, and cvode_bit
//   (only what the plan uses is instantiated: compiling the driver is the expensive part)
//
// PLAN, one directive per line:
//     span T0 T1                    the time span
//     timing TARGET REPEATS         seconds per timed loop, number of repeats (>= 5)
//     autonomous 0|1                rodas4 skips df/dt when the model has no driving torque
//     exact I1 I2 I3 W1 W2 W3 PHI THETA PSI   an exact reference: the free body (principal
//                                   moments, body omega and z-x-z angles at T0)
//     reference V RTOL RTOL_CHECK   DOP853 in long double on variant V at RTOL (the reference if
//                                   there is no exact one) and at RTOL_CHECK (its error estimate)
//     run V PEER METHOD SCALAR TOL STEP        one configuration (rotgen|odeint|cvode)
//     drift V METHOD TOL STEP T_END SAMPLES LABEL   a long run: relative energy error over time
// OUT, one record per line (whitespace separated, numbers with 21 significant digits):
//     compared NAME...              the quantities in the error's max-norm
//     reference SOURCE ERROR_ESTIMATE ORIENTATION_ESTIMATE
//     row V PEER METHOD FORM SCALAR TOL STEP STATUS ERROR ORIENTATION RHS JAC STEPS MEDIAN MIN
//         MAX ENERGY_DRIFT MOMENTUM_DRIFT N Y1..YN
//     drift LABEL STEPS RHS T RELATIVE_ENERGY_ERROR
#pragma once

#include "common_state.hpp"
#include "exact_reference.hpp"
#include "peers.hpp"
#include "run_record.hpp"
#include "timing.hpp"

#include <rotgen.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
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
};

template <class V, class T, class Method>
run_record run_method(const Method& m, const run_spec& spec, const driver_settings& s) {
    using system = variant_system<V, T>;
    using vector = state_vector<T, system>;
    struct state {
        system sys;
        Method method;
        vector y0, y;
        integration_result<T> r;
        T t0, t1;
    };
    const auto st = std::make_shared<state>(state{system{V::template parameters<T>()}, m,
                                                  initial_state<V, T>(), initial_state<V, T>(),
                                                  integration_result<T>{}, T(s.t0), T(s.t1)});
    // one integration from the initial state (the same code runs untimed and timed)
    auto once = [st]() -> double {
        st->y = st->y0;
        st->r = integrate(st->sys, st->method, st->t0, st->y, st->t1);
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
    return rec;
}

// rotgen's methods, one bit each.
enum method_bit : unsigned {
    rk4_bit = 1,
    dopri5_bit = 2,
    dop853_bit = 4,
    midpoint_bit = 8,
    rodas4_bit = 16
};
inline constexpr unsigned cvode_bit = 8; // in V::peers, beside the odeint_method bits

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
            m.max_steps = budget;
            return run_method<V, T>(m, spec, s);
        }
    if constexpr ((Mask & dop853_bit) != 0)
        if (spec.method == "dop853") {
            dop853<T> m(tol, tol);
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
            m.autonomous = s.autonomous;
            m.max_steps = budget;
            return run_method<V, T>(m, spec, s);
        }
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
                                                    odeint_initial_step<V>(spec, s));
        if constexpr ((V::peers & odeint_rkf78) != 0)
            if (spec.method == "rkf78")
                return run_odeint<V, odeint_rkf78>(
                    spec, s.t0, s.t1, spec.step > 0 ? 0.0 : odeint_initial_step<V>(spec, s));
        if constexpr ((V::peers & odeint_rk4) != 0)
            if (spec.method == "rk4") return run_odeint<V, odeint_rk4>(spec, s.t0, s.t1, spec.step);
    }
    if constexpr ((V::peers & cvode_bit) != 0)
        if (spec.peer == "cvode" && spec.scalar == "double") return run_cvode<V>(spec, s.t0, s.t1);
    run_record rec;
    rec.spec = spec;
    rec.status = "not_compiled";
    return rec;
}

// ---- dispatch over the variants of this translation unit ---------------------------------------

template <class Tuple, class F, std::size_t... I>
void with_variant_impl(int index, F&& f, std::index_sequence<I...>) {
    ((index == int(I) ? (f(static_cast<std::tuple_element_t<I, Tuple>*>(nullptr)), 0) : 0), ...);
}
// Calls f(static_cast<V*>(nullptr)) for the variant with this index.
template <class Tuple, class F> void with_variant(int index, F&& f) {
    with_variant_impl<Tuple>(index, f, std::make_index_sequence<std::tuple_size_v<Tuple>>{});
}

template <class V> common_state common_of(const std::vector<long double>& y) {
    common_state c;
    if (y.size() == V::state_size) V::common(y.data(), c);
    return c;
}

template <class V> std::vector<long double> initial_vector() {
    const auto a = V::initial();
    return std::vector<long double>(a.begin(), a.end());
}

inline std::string number(long double x) {
    if (std::isnan(x)) return "nan";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.21Lg", x);
    return buf;
}

// Energy and momentum drift between the initial and the final state, relative to the initial
// values (the momenta's to the largest of them).
template <class V> std::pair<long double, long double> drifts(const std::vector<long double>& y) {
    const auto y0 = initial_vector<V>();
    const long double nan = std::numeric_limits<long double>::quiet_NaN();
    long double e0 = 0, e1 = 0, ed = nan, md = nan;
    if (y.size() == V::state_size && V::energy(y0.data(), &e0) && V::energy(y.data(), &e1))
        ed = std::abs(e1 - e0) / std::max(std::abs(e0), 1e-300L);
    std::array<long double, 3> p0{}, p1{};
    const int n = y.size() == V::state_size ? V::momenta(y0.data(), p0.data()) : 0;
    if (n > 0) {
        V::momenta(y.data(), p1.data());
        long double scale = 0, d = 0;
        for (int i = 0; i < n; ++i) {
            scale = std::max(scale, std::abs(p0[static_cast<std::size_t>(i)]));
            d = std::max(
                d, std::abs(p1[static_cast<std::size_t>(i)] - p0[static_cast<std::size_t>(i)]));
        }
        md = d / std::max(scale, 1e-300L);
    }
    return {ed, md};
}

// ---- long runs: the energy error over time ---------------------------------------------------

template <class V, class Method>
void drift_run(const Method& m, const driver_settings& s, double t_end, int samples,
               const std::string& label, std::ostream& out) {
    using system = variant_system<V, double>;
    const system sys{V::template parameters<double>()};
    auto y = initial_state<V, double>();
    const auto y0l = V::initial();
    long double e0 = 0;
    if (!V::energy(y0l.data(), &e0)) return;
    // sample times: for fixed steps on the grid t0 + k h (k log-spaced, so the samples are the
    // method's own states), otherwise log-spaced in time (dense output)
    std::vector<double> times;
    double h = 0;
    if constexpr (!Method::adaptive) h = double(m.step);
    if (h > 0) {
        const long n = std::lround((t_end - s.t0) / h);
        long last = 0;
        for (int j = 0; j < samples; ++j) {
            const long k = std::lround(std::pow(double(n), double(j + 1) / double(samples)));
            if (k > last && k <= n) times.push_back(s.t0 + double(k) * h), last = k;
        }
    } else {
        const double span = t_end - s.t0;
        for (int j = 0; j < samples; ++j)
            times.push_back(s.t0 + span * std::pow(1e-4, 1.0 - double(j + 1) / double(samples)));
    }
    std::vector<std::pair<double, long double>> series;
    const auto r = integrate(sys, m, s.t0, y, times, [&](double t, const auto& yt) {
        std::array<long double, V::state_size> yl;
        for (std::size_t i = 0; i < V::state_size; ++i)
            yl[i] = yt[static_cast<Eigen::Index>(i)];
        long double e = 0;
        V::energy(yl.data(), &e);
        series.push_back({t, std::abs(e - e0) / std::max(std::abs(e0), 1e-300L)});
    });
    for (const auto& [t, e] : series)
        out << "drift " << label << " " << r.stats.steps << " " << r.stats.rhs_evals << " "
            << number(t) << " " << number(e) << "\n";
    if (!r.ok()) out << "drift_failed " << label << " " << status_name(r.code) << "\n";
}

template <class V>
void drift_one(const std::string& method, double tol, double step, const driver_settings& s,
               double t_end, int samples, const std::string& label, std::ostream& out) {
    constexpr unsigned mask = V::drift_methods;
    const std::size_t budget = 100000000;
    (void)tol, (void)step, (void)budget;
    if constexpr ((mask & rk4_bit) != 0)
        if (method == "rk4") {
            rk4<double> m;
            m.step = step;
            m.max_steps = budget;
            return drift_run<V>(m, s, t_end, samples, label, out);
        }
    if constexpr ((mask & midpoint_bit) != 0)
        if (method == "implicit_midpoint") {
            implicit_midpoint<double> m;
            m.step = step;
            m.max_steps = budget;
            return drift_run<V>(m, s, t_end, samples, label, out);
        }
    if constexpr ((mask & dopri5_bit) != 0)
        if (method == "dopri5") {
            dopri5<double> m(tol, tol);
            m.max_steps = budget;
            return drift_run<V>(m, s, t_end, samples, label, out);
        }
    if constexpr ((mask & dop853_bit) != 0)
        if (method == "dop853") {
            dop853<double> m(tol, tol);
            m.max_steps = budget;
            return drift_run<V>(m, s, t_end, samples, label, out);
        }
    out << "drift_failed " << label << " not_compiled\n";
}

// ---- the driver ---------------------------------------------------------------------------------

struct drift_spec {
    int variant;
    std::string method;
    double tol, step, t_end;
    int samples;
    std::string label;
};

// The plan's directives (see the top of this file).
struct driver_plan {
    driver_settings s;
    std::optional<free_body_exact<long double>> exact;
    int ref_variant = -1;
    double ref_rtol = 0, ref_check = 0;
    std::vector<run_spec> runs;
    std::vector<drift_spec> drift_runs;
};

using compared_set = std::array<bool, n_quantities>;

// One directive into p; false (after a message) on a malformed line.
inline bool read_plan_line(const std::string& line, driver_plan& p) {
    std::istringstream in(line);
    std::string what;
    if (!(in >> what) || what[0] == '#') return true;
    if (what == "span") {
        in >> p.s.t0 >> p.s.t1;
    } else if (what == "timing") {
        in >> p.s.target >> p.s.repeats;
    } else if (what == "autonomous") {
        int a = 1;
        in >> a;
        p.s.autonomous = a != 0;
    } else if (what == "exact") {
        std::array<long double, 3> I{}, w{};
        long double phi = 0, theta = 0, psi = 0;
        in >> I[0] >> I[1] >> I[2] >> w[0] >> w[1] >> w[2] >> phi >> theta >> psi;
        p.exact.emplace(I, w, euler_matrix(phi, theta, psi));
    } else if (what == "reference") {
        in >> p.ref_variant >> p.ref_rtol >> p.ref_check;
    } else if (what == "run") {
        run_spec r;
        in >> r.variant >> r.peer >> r.method >> r.scalar >> r.tol >> r.step;
        p.runs.push_back(r);
    } else if (what == "drift") {
        drift_spec d;
        in >> d.variant >> d.method >> d.tol >> d.step >> d.t_end >> d.samples >> d.label;
        p.drift_runs.push_back(d);
    }
    if (!in) {
        std::cerr << "bad plan line: " << line << "\n";
        return false;
    }
    return true;
}

// The compared quantities: those every variant in the plan determines. Writes `compared ...`.
template <class Variants> compared_set write_compared(const driver_plan& p, std::ostream& out) {
    compared_set compared;
    compared.fill(true);
    bool all_have_A = true;
    std::vector<bool> used(std::tuple_size_v<Variants>, false);
    for (const auto& r : p.runs)
        used[static_cast<std::size_t>(r.variant)] = true;
    for (std::size_t v = 0; v < used.size(); ++v) {
        if (!used[v]) continue;
        with_variant<Variants>(int(v), [&](auto* tag) {
            using V = std::remove_pointer_t<decltype(tag)>;
            const common_state c = common_of<V>(initial_vector<V>());
            for (int q = 0; q < n_quantities; ++q)
                compared[static_cast<std::size_t>(q)] =
                    compared[static_cast<std::size_t>(q)] && c.has[static_cast<std::size_t>(q)];
            all_have_A = all_have_A && c.has_A;
        });
    }
    out << "compared";
    for (int q = 0; q < n_quantities; ++q)
        if (compared[static_cast<std::size_t>(q)]) out << " " << quantity_name(q);
    out << (all_have_A ? " (attitude everywhere)" : "") << "\n";
    return compared;
}

// DOP853 in long double on the reference variant at ref_rtol (into ref) and ref_check (into
// check); false when that variant has no long double DOP853.
template <class Variants>
bool long_double_reference(const driver_plan& p, common_state& ref, common_state& check,
                           std::ostream& out) {
    bool have_check = false;
    with_variant<Variants>(p.ref_variant, [&](auto* tag) {
        using V = std::remove_pointer_t<decltype(tag)>;
        if constexpr ((V::long_double_methods & dop853_bit) != 0) {
            using system = variant_system<V, long double>;
            const system sys{V::template parameters<long double>()};
            for (int pass = 0; pass < 2; ++pass) {
                auto y = initial_state<V, long double>();
                const double rtol = pass ? p.ref_check : p.ref_rtol;
                dop853<long double> m(rtol, rtol);
                m.max_steps = 100000000;
                const auto r = integrate(sys, m, (long double)p.s.t0, y, (long double)p.s.t1);
                std::vector<long double> yl(y.data(), y.data() + y.size());
                (pass ? check : ref) = common_of<V>(yl);
                out << "reference_run " << rtol << " " << status_name(r.code) << " "
                    << r.stats.steps << "\n";
            }
            have_check = true;
        }
    });
    return have_check;
}

// The free body's exact state at t1.
inline common_state exact_state(const free_body_exact<long double>& exact, double t1) {
    common_state e;
    const auto w = exact.omega((long double)t1);
    e.set(q_omega1, w[0]);
    e.set(q_omega2, w[1]);
    e.set(q_omega3, w[2]);
    e.set_rotation(exact.rotation((long double)t1));
    e.angles_from_rotation();
    e.rates_from_omega();
    return e;
}

// The reference at the end time, and the line `reference SOURCE ERROR ORIENTATION`.
template <class Variants>
common_state write_reference(const driver_plan& p, const compared_set& compared,
                             std::ostream& out) {
    common_state ref, check;
    bool have_check = false;
    if (p.ref_variant >= 0) have_check = long_double_reference<Variants>(p, ref, check, out);
    if (p.exact) {
        // the exact reference; the DOP853 run above, if any, is its cross-check
        const common_state e = exact_state(*p.exact, p.s.t1);
        if (p.ref_variant >= 0) check = ref;
        ref = e;
        out << "reference exact_" << p.exact->kind_name() << " "
            << number(have_check ? state_error(check, ref, compared) : NAN) << " "
            << number(have_check ? attitude_error(check, ref) : NAN) << "\n";
    } else if (have_check) {
        out << "reference dop853_long_double " << number(state_error(check, ref, compared)) << " "
            << number(attitude_error(check, ref)) << "\n";
    } else {
        out << "reference none nan nan\n";
    }
    return ref;
}

// One `row ...` line: the configuration, its errors against ref, counters, times, drifts, state.
template <class V>
void write_row(const run_record& rec, const common_state& ref, const compared_set& compared,
               std::ostream& out) {
    const run_spec& spec = rec.spec;
    const common_state c = common_of<V>(rec.y);
    const long double nan = std::numeric_limits<long double>::quiet_NaN();
    const bool ok = rec.status == "ok";
    const long double err = ok ? state_error(c, ref, compared) : nan;
    const long double orient = ok ? attitude_error(c, ref) : nan;
    const auto [ed, md] = ok ? drifts<V>(rec.y) : std::pair<long double, long double>{nan, nan};
    out << "row " << spec.variant << " " << spec.peer << " " << spec.method << " " << V::form << " "
        << spec.scalar << " " << number(spec.tol) << " " << number(spec.step) << " " << rec.status
        << " " << number(err) << " " << number(orient) << " " << rec.rhs_evals << " "
        << rec.jac_evals << " " << rec.steps << " " << number(rec.time.median) << " "
        << number(rec.time.min) << " " << number(rec.time.max) << " " << number(ed) << " "
        << number(md) << " " << rec.y.size();
    for (long double v : rec.y)
        out << " " << number(v);
    out << "\n";
}

// The sweep: every configuration run once (final state, counters), then timed in rounds.
template <class Variants>
void run_sweep(const driver_plan& p, const common_state& ref, const compared_set& compared,
               std::ostream& out) {
    std::vector<run_record> records;
    records.reserve(p.runs.size());
    for (const auto& spec : p.runs)
        with_variant<Variants>(spec.variant, [&](auto* tag) {
            using V = std::remove_pointer_t<decltype(tag)>;
            records.push_back(run_one<V>(spec, p.s));
            calibrate(records.back().job, p.s.target);
        });
    for (int round = 0; round < p.s.repeats; ++round)
        for (auto& rec : records)
            sample(rec.job);
    for (auto& rec : records) {
        rec.time = summary(rec.job);
        rec.job.once = nullptr; // release the configuration's state (CVODE memory, ...)
        with_variant<Variants>(rec.spec.variant, [&](auto* tag) {
            write_row<std::remove_pointer_t<decltype(tag)>>(rec, ref, compared, out);
        });
    }
}

template <class Variants> int run_driver(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: " << argv[0] << " PLAN OUT\n";
        return 2;
    }
    std::ifstream plan(argv[1]);
    std::ofstream out(argv[2]);
    if (!plan || !out) {
        std::cerr << "cannot open the plan or the output\n";
        return 2;
    }
    driver_plan p;
    std::string line;
    while (std::getline(plan, line))
        if (!read_plan_line(line, p)) return 2;

    const compared_set compared = write_compared<Variants>(p, out);
    const common_state ref = write_reference<Variants>(p, compared, out);
    out.flush();
    run_sweep<Variants>(p, ref, compared, out);
    out.flush();
    // Long runs.
    for (const auto& d : p.drift_runs) {
        with_variant<Variants>(d.variant, [&](auto* tag) {
            using V = std::remove_pointer_t<decltype(tag)>;
            drift_one<V>(d.method, d.tol, d.step, p.s, d.t_end, d.samples, d.label, out);
        });
        out.flush();
    }
    return 0;
}

} // namespace rotgen::bench
