// rotgen bench: making the plan.
#include "bench/plan.hpp"

#include "bench/numbers.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace rotgen::bench {

std::vector<double> taylor_tolerances() {
    return {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15};
}

namespace {

// The method bits of bench/workprecision/runners.hpp (method_bit, cvode_bit) and peers.hpp
// (odeint_method).
unsigned method_bit(const std::string& method) {
    if (method == "rk4") return 1;
    if (method == "dopri5") return 2;
    if (method == "dop853") return 4;
    if (method == "implicit_midpoint") return 8;
    if (method == "rodas4") return 16;
    if (method == "split2") return 32;
    if (method == "split4") return 64;
    if (method == "split6") return 128;
    if (method == "taylor") return 256;
    throw std::logic_error("bench: unknown method " + method);
}
unsigned peer_bit(const std::string& peer, const std::string& method) {
    if (peer == "cvode") return 8;
    return method == "dopri5" ? 1 : method == "rkf78" ? 2 : 4;
}

// The plan's text, and what each variant must compile for it.
struct plan_builder {
    std::ostringstream text;
    std::vector<variant>* variants = nullptr;
    std::size_t lines = 0;
    void run(std::size_t v, const std::string& peer, const std::string& method,
             const std::string& scalar, double tol, double step) {
        text << "run " << v << " " << peer << " " << method << " " << scalar << " " << plain(tol)
             << " " << plain(step) << "\n";
        variant& x = (*variants)[v];
        if (peer != "rotgen")
            x.peers |= peer_bit(peer, method);
        else
            (scalar == "float"         ? x.float_methods
             : scalar == "long_double" ? x.long_double_methods
                                       : x.double_methods) |= method_bit(method);
        ++lines;
    }
};

// The tolerances and steps of the sweep.
struct sweep_grid {
    std::vector<double> tols_all, tols_odd, tols_rodas, tols_bdf, tols_float, tols_long;
    std::vector<double> tols_split2, tols_taylor;
    std::vector<double> rk4_steps, rk4_alt, mid_steps, mid_alt, high_steps;
    double target = 0.02; // seconds per timed loop
};

// nu = max(|omega|, |q_dot_i|, 1e-3): the fastest rate of the motion.
double fastest_rate(const kinematics& k0) {
    double nu = 0;
    for (int i = 0; i < 3; ++i) {
        nu += double(k0.omega[static_cast<std::size_t>(i)] * k0.omega[static_cast<std::size_t>(i)]);
    }
    nu = std::sqrt(nu);
    if (k0.have_rates)
        for (int i = 0; i < 3; ++i)
            nu = std::max(nu, double(std::abs(k0.qd[static_cast<std::size_t>(i)])));
    return std::max(nu, 1e-3);
}

sweep_grid make_grid(double span, double nu, bool quick) {
    // steps h = c / nu, snapped to span / N
    const auto steps_for = [&](const std::vector<double>& cs) {
        std::vector<double> hs;
        for (double c : cs) {
            const double n = std::ceil(span / (c / nu));
            if (n < 10 || n > 2e6) continue;
            hs.push_back(span / n);
        }
        return hs;
    };
    sweep_grid g;
    g.tols_all = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13};
    g.tols_odd = {1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-13};
    g.tols_rodas = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
    g.tols_bdf = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
    g.tols_float = {1e-3, 1e-4, 1e-5};
    g.tols_long = {1e-3,  1e-4,  1e-5,  1e-6,  1e-7,  1e-8, 1e-9,
                   1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15};
    // split2's step goes as rtol^(1/2): 1e-9 already takes 4e5 steps of the heavy top (t = 0..10)
    g.tols_split2 = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9};
    g.tols_taylor = taylor_tolerances();
    g.rk4_steps = steps_for({0.3, 0.1, 0.03, 0.01, 0.003, 0.001, 0.0003});
    g.rk4_alt = steps_for({0.1, 0.01, 0.001});
    g.mid_steps = steps_for({0.3, 0.1, 0.03, 0.01, 0.003});
    g.mid_alt = steps_for({0.1, 0.01});
    // DOP853 (and Odeint's Fehlberg 7(8)) with fixed steps: what error control costs
    g.high_steps = steps_for({1.5, 1, 0.7, 0.5, 0.35, 0.25, 0.18, 0.12});
    if (quick) {
        g.tols_all = {1e-5, 1e-8};
        g.tols_odd = {1e-8};
        g.tols_rodas = {1e-5};
        g.tols_bdf = {1e-6};
        g.tols_float = {1e-4};
        g.tols_long = {1e-12};
        g.tols_split2 = g.tols_taylor = g.tols_all;
        g.rk4_steps = g.mid_steps = steps_for({0.03});
        g.high_steps = steps_for({0.5});
        g.rk4_alt.clear();
        g.mid_alt.clear();
        g.target = 0.002;
    }
    return g;
}

// The principal moments of a free body with a diagonal inertia tensor (whose motion the driver
// knows exactly), none otherwise.
std::optional<std::array<long double, 3>>
principal_moments(const model_spec& spec, const GiNaC::exmap& parameter_values, bool conservative) {
    bool principal_free =
        conservative && spec.inertia_diagonal && spec.potential.is_zero() && !spec.gravity;
    if (!principal_free) return std::nullopt;
    std::array<long double, 3> moments{};
    const scoped_digits digits(30);
    for (int i = 0; i < 3; ++i) {
        const GiNaC::ex m = spec.inertia[i][i].subs(parameter_values);
        moments[static_cast<std::size_t>(i)] = to_long_double(m);
        principal_free = principal_free && moments[static_cast<std::size_t>(i)] > 0;
    }
    if (!principal_free) return std::nullopt;
    return moments;
}

// The reference: exact for a principal free body, DOP853 in long double at rtol 2e-18 (checked
// at 2e-16) on the first variant that determines the attitude. Returns that variant.
std::size_t plan_reference(plan_builder& plan, const model_spec& spec,
                           const GiNaC::exmap& parameter_values, const kinematics& k0,
                           bool conservative) {
    const auto moments = principal_moments(spec, parameter_values, conservative);
    std::vector<variant>& variants = *plan.variants;
    std::size_t ref_variant = 0;
    for (std::size_t i = 0; i < variants.size(); ++i)
        if (variants[i].has_A && variants[i].lowered) {
            ref_variant = i;
            break;
        }
    variants[ref_variant].long_double_methods |= method_bit("dop853");
    if (moments) {
        const auto& m = *moments;
        plan.text << "exact";
        for (long double x :
             {m[0], m[1], m[2], k0.omega[0], k0.omega[1], k0.omega[2], k0.q[0], k0.q[1], k0.q[2]})
            plan.text << " " << ld_plain(x);
        plan.text << "\n";
    }
    plan.text << "reference " << ref_variant << " 2e-18 2e-16\n";
    return ref_variant;
}

// The main variant's other scalar types and the peers on its kernels.
void plan_main(plan_builder& plan, std::size_t i, const sweep_grid& g, bool quick) {
    // (--quick: the fewest instantiations that still exercise every kind of run)
    for (double tol : g.tols_float) {
        if (!quick) plan.run(i, "rotgen", "dopri5", "float", tol, 0);
        plan.run(i, "rotgen", "dop853", "float", tol, 0);
    }
    for (std::size_t j = 0; j < g.rk4_steps.size() && j < 4 && !quick; ++j)
        plan.run(i, "rotgen", "rk4", "float", 0, g.rk4_steps[j]);
    for (double tol : g.tols_long) {
        if (!quick) plan.run(i, "rotgen", "dopri5", "long_double", tol, 0);
        plan.run(i, "rotgen", "dop853", "long_double", tol, 0);
    }
    for (std::size_t j = 0; j < g.rk4_steps.size() && j < 5 && !quick; ++j)
        plan.run(i, "rotgen", "rk4", "long_double", 0, g.rk4_steps[j]);
    // the peers, on the same kernels
    for (double tol : g.tols_all)
        plan.run(i, "odeint", "dopri5", "double", tol, 0);
    for (std::size_t j = 0; j < g.tols_all.size() && (j == 0 || !quick); ++j)
        plan.run(i, "odeint", "rkf78", "double", g.tols_all[j], 0);
    for (std::size_t j = 0; j < g.rk4_steps.size() && !quick; ++j)
        plan.run(i, "odeint", "rk4", "double", 0, g.rk4_steps[j]);
    for (double h : g.high_steps) {
        plan.run(i, "rotgen", "dop853", "double", 0, h);
        plan.run(i, "odeint", "rkf78", "double", 0, h);
    }
    for (double tol : g.tols_all)
        plan.run(i, "cvode", "adams", "double", tol, 0);
    for (double tol : g.tols_bdf)
        plan.run(i, "cvode", "bdf", "double", tol, 0);
}

// The configurations of variant i: the explicit methods in double for every variant (the other
// forms: dop853, rk4, midpoint), the implicit ones where they run, and plan_main for the main.
void plan_variant(plan_builder& plan, std::size_t i, const sweep_grid& g, bool quick) {
    const variant& v = (*plan.variants)[i];
    const bool is_main = v.r == role::main;
    const bool explicit_only = v.r == role::runtime || v.r == role::unlowered;
    const bool implicit_runs = v.implicit_runs;
    const auto& tols = is_main || explicit_only ? g.tols_all : g.tols_odd;
    for (double h : is_main || explicit_only ? g.rk4_steps : g.rk4_alt)
        plan.run(i, "rotgen", "rk4", "double", 0, h);
    if (is_main || (explicit_only && !quick))
        for (double tol : tols)
            plan.run(i, "rotgen", "dopri5", "double", tol, 0);
    for (double tol : tols)
        plan.run(i, "rotgen", "dop853", "double", tol, 0);
    if (!explicit_only && implicit_runs) {
        for (double h : is_main ? g.mid_steps : g.mid_alt)
            plan.run(i, "rotgen", "implicit_midpoint", "double", 0, h);
        for (double tol : is_main ? g.tols_rodas : std::vector<double>{})
            plan.run(i, "rotgen", "rodas4", "double", tol, 0);
    }
    if (is_main) plan_main(plan, i, g, quick);
}

// split2/4/6 on the body form with the quaternion (under error control at each tolerance, as
// simulate runs them given rtol), taylor on the main variant; or
// why each is left out (the refusal simulate gives), as a comment line and in p.left_out.
void plan_split_taylor(plan_builder& plan, bench_plan& p, const sweep_grid& g,
                       const split_taylor_methods& m) {
    const auto sv = split_variant(*plan.variants);
    if (m.split_refusal || !sv) {
        p.left_out.push_back("split2, split4, split6: " +
                             m.split_refusal.value_or("the model has no body form with the "
                                                      "quaternion, which they run"));
    } else {
        plan.text << "moments " << plain(m.moments[0]) << " " << plain(m.moments[1]) << " "
                  << plain(m.moments[2]) << "\n";
        for (double tol : g.tols_split2)
            plan.run(*sv, "rotgen", "split2", "double", tol, 0);
        for (const char* method : {"split4", "split6"})
            for (double tol : g.tols_all)
                plan.run(*sv, "rotgen", method, "double", tol, 0);
    }
    if (m.taylor_refusal)
        p.left_out.push_back("taylor: " + *m.taylor_refusal);
    else
        for (double tol : g.tols_taylor)
            plan.run(0, "rotgen", "taylor", "double", tol, 0);
    for (const auto& why : p.left_out)
        plan.text << "# left out: " << why << "\n";
}

// The long runs: long_steps steps of h = 0.3 / nu (large enough that the explicit methods' drift
// shows within the run), on the Hamiltonian variant and the main one.
void plan_long_runs(plan_builder& plan, bench_plan& p, const bench_options& opt,
                    const variant_set& set) {
    std::vector<variant>& variants = *plan.variants;
    const double h = 0.3 / p.nu;
    const double t_end = p.t0 + double(opt.long_steps) * h;
    const int samples = opt.quick ? 40 : 300;
    const auto drift = [&](std::size_t v, const std::string& method, double tol, double step) {
        std::string label = method + ":" + variants[v].label + ":" +
                            (step > 0 ? "h=" + short_number(step, 3) : "tol=" + tol_text(tol));
        plan.text << "drift " << v << " " << method << " " << plain(tol) << " " << plain(step)
                  << " " << plain(t_end) << " " << samples << " " << label << "\n";
        p.drift_labels.push_back(label);
        variants[v].drift_methods |= method_bit(method);
    };
    const std::size_t hv = set.hamiltonian ? *set.hamiltonian : 0;
    drift(hv, "implicit_midpoint", 0, h);
    drift(hv, "rk4", 0, h);
    if (!opt.quick) {
        drift(hv, "dopri5", 1e-8, 0);
        drift(hv, "dop853", 1e-8, 0);
    }
    if (hv != 0) {
        drift(0, "implicit_midpoint", 0, h);
        drift(0, "rk4", 0, h);
    }
}

} // namespace

bench_plan make_plan(const scene_spec& scene, const model_spec& spec,
                     const GiNaC::exmap& parameter_values, const kinematics& k0,
                     const bench_options& opt, bool conservative, variant_set& set,
                     const split_taylor_methods& extra) {
    bench_plan p;
    p.t0 = scene.t_start;
    p.t1 = scene.t_end;
    p.nu = fastest_rate(k0);
    const sweep_grid g = make_grid(p.t1 - p.t0, p.nu, opt.quick);
    p.target = g.target;
    plan_builder plan;
    plan.variants = &set.variants;
    plan.text << "span " << plain(p.t0) << " " << plain(p.t1) << "\n"
              << "samples " << scene.samples << "\n"
              << "timing " << plain(p.target) << " " << p.repeats << "\n"
              << "autonomous " << (spec.has_torque ? 0 : 1) << "\n";
    p.ref_variant = plan_reference(plan, spec, parameter_values, k0, conservative);
    for (std::size_t i = 0; i < set.variants.size(); ++i)
        plan_variant(plan, i, g, opt.quick);
    plan_split_taylor(plan, p, g, extra);
    if (opt.long_steps > 0 && set.variants[0].has_energy && conservative)
        plan_long_runs(plan, p, opt, set);
    p.text = plan.text.str();
    p.lines = plan.lines;
    return p;
}

} // namespace rotgen::bench
