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
//     taylor_series, taylor(t, c, order, p)   the Taylor coefficients (a variant the plan runs
//                                   taylor on; split_taylor.hpp)
//     double_methods, float_methods, long_double_methods, drift_methods   bit masks of rotgen's
//                                   methods (method_bit) the plan uses with each scalar type
//     peers                         bit mask: odeint_method bits, and cvode_bit
//   (only what the plan uses is instantiated: compiling the driver is the expensive part)
//
// PLAN, one directive per line:
//     span T0 T1                    the time span
//     samples N                     the scene's N sample times, evenly from T0 to T1 (the error's)
//     timing TARGET REPEATS         seconds per timed loop, number of repeats (>= 5)
//     autonomous 0|1                rodas4 skips df/dt when the model has no driving torque
//     exact I1 I2 I3 W1 W2 W3 PHI THETA PSI   an exact reference: the free body (principal
//                                   moments, body omega and z-x-z angles at T0)
//     moments I1 I2 I3              the principal moments the split methods use (split_taylor.hpp)
//     reference V RTOL RTOL_CHECK   DOP853 in long double on variant V at RTOL (the reference if
//                                   there is no exact one) and at RTOL_CHECK (its error estimate)
//     run V PEER METHOD SCALAR TOL STEP        one configuration (rotgen|odeint|cvode)
//     drift V METHOD TOL STEP T_END SAMPLES LABEL   a long run: relative energy error over time
// OUT, one record per line (whitespace separated, numbers with 21 significant digits):
//     compared NAME...              the quantities the error compares (common_state.hpp)
//     reference SOURCE ERROR_ESTIMATE ORIENTATION_ESTIMATE   (the floor: the check run's error)
//     row V PEER METHOD FORM SCALAR TOL STEP STATUS ERROR ORIENTATION RHS JAC STEPS MEDIAN MIN
//         MAX ENERGY_DRIFT MOMENTUM_DRIFT N Y1..YN
//     drift LABEL STEPS RHS T RELATIVE_ENERGY_ERROR
// ERROR and ORIENTATION are the sampled error (common_state.hpp: max over the samples of the
// attitude angle and |omega - omega_ref| / max |omega_ref|) and the largest attitude angle, each
// run's samples against the reference's.
// The pieces: runners.hpp and run_one.hpp (one configuration: rotgen's integrators, and the
// peers of peers.hpp), drift.hpp (the long runs), common_state.hpp and exact_reference.hpp (the
// error), timing.hpp.
#pragma once

#include "common_state.hpp"
#include "drift.hpp"
#include "exact_reference.hpp"
#include "run_one.hpp"
#include "run_record.hpp"
#include "runners.hpp"
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

// The common representation of each sample.
template <class V>
std::vector<common_state> common_samples(const std::vector<std::vector<long double>>& ys) {
    std::vector<common_state> c;
    c.reserve(ys.size());
    for (const auto& y : ys)
        c.push_back(common_of<V>(y));
    return c;
}

template <class V> std::vector<long double> initial_vector() {
    const auto a = V::initial();
    return std::vector<long double>(a.begin(), a.end());
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

// One directive into p; false (after a message) on a malformed line.
inline bool read_plan_line(const std::string& line, driver_plan& p) {
    std::istringstream in(line);
    std::string what;
    if (!(in >> what) || what[0] == '#') return true;
    if (what == "span") {
        in >> p.s.t0 >> p.s.t1;
    } else if (what == "samples") {
        long n = 0;
        in >> n;
        p.s.times.assign(static_cast<std::size_t>(std::max(n, 2L)), p.s.t0);
        for (std::size_t i = 0; i < p.s.times.size(); ++i) // as run/engine.hpp's sample_times
            p.s.times[i] = i + 1 == p.s.times.size() ? p.s.t1
                                                     : p.s.t0 + (p.s.t1 - p.s.t0) * double(i) /
                                                                    double(p.s.times.size() - 1);
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
    } else if (what == "moments") {
        in >> p.s.moments[0] >> p.s.moments[1] >> p.s.moments[2];
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
template <class Variants> comparison write_compared(const driver_plan& p, std::ostream& out) {
    std::array<bool, n_quantities> compared;
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
    return comparison{compared, all_have_A};
}

// DOP853 in long double on the reference variant at ref_rtol (into ref) and ref_check (into
// check), each at the sample times; false when that variant has no long double DOP853.
template <class Variants>
bool long_double_reference(const driver_plan& p, std::vector<common_state>& ref,
                           std::vector<common_state>& check, std::ostream& out) {
    bool have_check = false;
    with_variant<Variants>(p.ref_variant, [&](auto* tag) {
        using V = std::remove_pointer_t<decltype(tag)>;
        if constexpr ((V::long_double_methods & dop853_bit) != 0) {
            using system = variant_system<V, long double>;
            const system sys{V::template parameters<long double>()};
            for (int pass = 0; pass < 2; ++pass) {
                const double rtol = pass ? p.ref_check : p.ref_rtol;
                dop853<long double> m(rtol, rtol);
                m.max_steps = 100000000;
                (pass ? check : ref) = common_samples<V>(sampled_states<long double>(
                    sys, m, initial_state<V, long double>(), p.s.times));
                out << "reference_run " << rtol << " "
                    << ((pass ? check : ref).empty() ? "failed" : "ok") << "\n";
            }
            have_check = true;
        }
    });
    return have_check;
}

// The free body's exact state at t.
inline common_state exact_state(const free_body_exact<long double>& exact, double t) {
    common_state e;
    const auto w = exact.omega((long double)t);
    e.set(q_omega1, w[0]);
    e.set(q_omega2, w[1]);
    e.set(q_omega3, w[2]);
    e.set_rotation(exact.rotation((long double)t));
    e.angles_from_rotation();
    e.rates_from_omega();
    return e;
}

// The reference at the samples, and the line `reference SOURCE ERROR ORIENTATION`: the check
// run's sampled error against it (the reference's floor).
template <class Variants>
std::vector<common_state> write_reference(const driver_plan& p, const comparison& compared,
                                          std::ostream& out) {
    std::vector<common_state> ref, check;
    bool have_check = false;
    if (p.ref_variant >= 0) have_check = long_double_reference<Variants>(p, ref, check, out);
    const long double nan = std::numeric_limits<long double>::quiet_NaN();
    if (p.exact) {
        // the exact reference; the DOP853 run above, if any, is its cross-check
        std::vector<common_state> e;
        for (double t : p.s.times)
            e.push_back(exact_state(*p.exact, t));
        if (p.ref_variant >= 0) check = ref;
        ref = e;
        const sampled_measure m =
            have_check ? sampled_error(check, ref, compared) : sampled_measure{nan, nan};
        out << "reference exact_" << p.exact->kind_name() << " " << number(m.error) << " "
            << number(m.orientation) << "\n";
    } else if (have_check) {
        const sampled_measure m = sampled_error(check, ref, compared);
        out << "reference dop853_long_double " << number(m.error) << " " << number(m.orientation)
            << "\n";
    } else {
        out << "reference none nan nan\n";
    }
    return ref;
}

// One `row ...` line: the configuration, its sampled errors, counters, times, drifts, state.
template <class V> void write_row(const run_record& rec, std::ostream& out) {
    const run_spec& spec = rec.spec;
    const long double nan = std::numeric_limits<long double>::quiet_NaN();
    const bool ok = rec.status == "ok";
    const auto [ed, md] = ok ? drifts<V>(rec.y) : std::pair<long double, long double>{nan, nan};
    out << "row " << spec.variant << " " << spec.peer << " " << spec.method << " " << V::form << " "
        << spec.scalar << " " << number(spec.tol) << " " << number(spec.step) << " " << rec.status
        << " " << number(ok ? rec.error : nan) << " " << number(ok ? rec.orientation : nan) << " "
        << rec.rhs_evals << " " << rec.jac_evals << " " << rec.steps << " "
        << number(rec.time.median) << " " << number(rec.time.min) << " " << number(rec.time.max)
        << " " << number(ed) << " " << number(md) << " " << rec.y.size();
    for (long double v : rec.y)
        out << " " << number(v);
    out << "\n";
}

// The sweep: every configuration run once (final state, counters) and once more at the samples
// (its error against ref, the samples then dropped), then timed in rounds.
template <class Variants>
void run_sweep(const driver_plan& p, const std::vector<common_state>& ref,
               const comparison& compared, std::ostream& out) {
    std::vector<run_record> records;
    records.reserve(p.runs.size());
    for (const auto& spec : p.runs)
        with_variant<Variants>(spec.variant, [&](auto* tag) {
            using V = std::remove_pointer_t<decltype(tag)>;
            records.push_back(run_one<V>(spec, p.s));
            run_record& rec = records.back();
            const sampled_measure m = sampled_error(common_samples<V>(rec.samples), ref, compared);
            rec.error = m.error, rec.orientation = m.orientation;
            rec.samples = {};
            calibrate(rec.job, p.s.target);
        });
    for (int round = 0; round < p.s.repeats; ++round)
        for (auto& rec : records)
            sample(rec.job);
    for (auto& rec : records) {
        rec.time = summary(rec.job);
        rec.job.once = nullptr; // release the configuration's state (CVODE memory, ...)
        with_variant<Variants>(rec.spec.variant, [&](auto* tag) {
            write_row<std::remove_pointer_t<decltype(tag)>>(rec, out);
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
    if (p.s.times.empty()) p.s.times = {p.s.t0, p.s.t1};

    const comparison compared = write_compared<Variants>(p, out);
    const std::vector<common_state> ref = write_reference<Variants>(p, compared, out);
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
