// The extremes of DESIGN.md "Extremes to hold" (issue 6): fast spin, nearly equal moments and
// extreme ratios, long runs, float vs double vs long double. Each test shows the behaviour that
// the scripts in bench/extremes/ measure over a wider range (their tables are in
// docs/performance.md, "Extremes: where the results hold"); the margins are stated next to the
// measured values.
#include "support.hpp"

#include "../../generated/free_asymmetric_top_body.hpp"
#include <exact_free_top.hpp>
#include <rotgen.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

using namespace rotgen::test;

namespace {

constexpr double pi = 3.141592653589793;

std::string scratch(const std::string& name) {
    return std::string(ROTGEN_BINARY_DIR) + "/" + name;
}

// A number from the summary: the field before `label` ("RHS", "accepted") or after it ("relative").
double summary_number(const std::string& out, const std::string& label) {
    const auto at = out.find(label);
    if (at == std::string::npos) throw std::runtime_error("no '" + label + "' in the summary");
    if (label.back() == ' ') return std::stod(out.substr(at + label.size()));
    const auto start = out.rfind(' ', at - 1);
    return std::stod(out.substr(start + 1, at - start - 1));
}
double rhs_evals(const std::string& out) {
    return summary_number(out, " RHS");
}
double relative_drift(const std::string& out, const std::string& invariant) {
    const auto at = out.find("drift   " + invariant + ":");
    if (at == std::string::npos) throw std::runtime_error("no drift of " + invariant);
    return summary_number(out.substr(at), "(relative ");
}

// Runs the scene `text` (written to scratch `name`), returns the summary; the CSV is `name`.csv.
run_result simulate(const std::string& name, const std::string& text) {
    const scratch_file scene(name + ".yaml", text);
    return run_rotgen("simulate '" + scene.path + "' -o '" + scratch(name + ".csv") + "'");
}

// The heavy top of models/heavy_top.yaml with g = 10 (M g h / I1 = 1: omega3/omega_g = omega3),
// released at theta0 = 0.5 with phi_dot = theta_dot = 0 and psi_dot = omega3.
std::string fast_top(const std::string& form, double omega3, double end, int samples,
                     const std::string& integrator) {
    std::ostringstream s;
    s.precision(17);
    s << "model: " << model_path("heavy_top") << "\nparameters: {g: 10}\nform: " << form
      << "\ninitial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: " << omega3
      << "}\ntime: {end: " << end << ", samples: " << samples << "}\nintegrator: {" << integrator
      << "}\nrecord: [theta, phi, p_phi, p_psi]\n";
    return s.str();
}

// theta1 - theta0 between the turning points of (5.79)'s effective potential for that release:
// u0 - u1 = c (1 - u1^2), c = 2 I1 M g h / (I3 omega3)^2, by Newton's method in d = theta1 -
// theta0.
double exact_nutation(double omega3) {
    const double c = 2 * 1.0 * 1.0 / ((0.5 * omega3) * (0.5 * omega3)), t0 = 0.5;
    double d = c * std::sin(t0);
    for (int i = 0; i < 30; ++i) {
        const double a = t0 + d;
        d -= (2 * std::sin(t0 + d / 2) * std::sin(d / 2) - c * std::sin(a) * std::sin(a)) /
             (std::sin(a) - 2 * c * std::sin(a) * std::cos(a));
    }
    return d;
}

std::string
free_top_scene(const std::string& form, const std::array<double, 3>& I,
               const std::string& integrator = "method: dop853, rtol: 1e-12, atol: 1e-14") {
    // omega(0) = (1, 0.1, 0.5); the space z axis along L = I omega(0), so theta stays clear of 0.
    const double L1 = I[0], L2 = 0.1 * I[1], L3 = 0.5 * I[2];
    std::ostringstream s;
    s.precision(17);
    s << "model: {name: free_top, parameters: {I1: 1, I2: 2, I3: 3}, inertia: [I1, I2, I3]}\n"
      << "parameters: {I1: " << I[0] << ", I2: " << I[1] << ", I3: " << I[2] << "}\nform: " << form
      << "\ninitial: {phi: 0, theta: " << std::atan2(std::hypot(L1, L2), L3)
      << ", psi: " << std::atan2(L1, L2)
      << ", omega1: 1, omega2: 0.1, omega3: 0.5}\ntime: {end: 100, samples: 1001}\n"
      << "integrator: {" << integrator << "}\nrecord: [omega1, omega2, omega3]\n";
    return s.str();
}

// max |omega - exact| over the CSV, exact in long double for the same double inputs, and the
// simulated and exact swings max |omega3(t) - omega3(0)|.
struct free_top_check {
    double error = 0, swing = 0, exact_swing = 0;
};
free_top_check check_free_top(const std::string& csv, const std::array<double, 3>& I) {
    const rotgen::free_top_exact<long double> exact({I[0], I[1], I[2]},
                                                    {1, (long double)0.1, (long double)0.5});
    const csv_table t = read_csv(csv);
    free_top_check c;
    const long double w30 = exact(0)[2];
    for (const auto& row : t.rows) {
        const auto e = exact(row[0]);
        for (int j = 0; j < 3; ++j)
            c.error =
                std::max(c.error, double(std::abs(row[1 + j] - e[static_cast<std::size_t>(j)])));
        c.swing = std::max(c.swing, std::abs(row[3] - t.rows.front()[3]));
        c.exact_swing = std::max(c.exact_swing, double(std::abs(e[2] - w30)));
    }
    return c;
}

} // namespace

// ---- fast spin ---------------------------------------------------------------------------------

TEST_CASE("fast spin 1e4: the nutation matches the effective potential, the cost follows the spin",
          "[extremes][fast_spin]") {
    // bench/extremes/fast_spin.sh: over 20 nutation periods, dop853 at rtol 1e-13 (an attitude
    // error of about 1e-13 rad: docs/integrators.md "What a tolerance means") resolves the nutation
    // amplitude (~3.8e-8 rad at omega3 = 1e4) to 1.5e-10 and 4.9e-9 relative at 1e3 and 1e4
    // (1000 samples per period: sampling alone may miss the peak by up to (pi/1000)^2/4 = 2.5e-6
    // relative, hence the margin 1e-5), and the fast-top estimate 2 I1 M g h sin(theta0)/(I3
    // omega3)^2 differs from the exact turning point by 1.05e-7. Invariants: measured 1.6e-15 ...
    // 3.3e-15 relative.
    double evals_per_period[2];
    int k = 0;
    for (double omega3 : {1e3, 1e4}) {
        const double period = 2 * pi / (0.5 * omega3);
        const run_result r =
            simulate("extremes_fast_spin", fast_top("lagrangian", omega3, 20 * period, 20001,
                                                    "method: dop853, rtol: 1e-13, atol: 1e-15"));
        INFO(r.out << r.err);
        REQUIRE(r.status == 0);
        const auto theta = read_csv(scratch("extremes_fast_spin.csv")).values("theta");
        const double amplitude = *std::max_element(theta.begin(), theta.end()) - 0.5;
        const double exact = exact_nutation(omega3),
                     estimate = 8 * std::sin(0.5) / (omega3 * omega3);
        CHECK(std::abs(amplitude - exact) < 1e-5 * exact);
        CHECK(std::abs(estimate - exact) < 2e-5 * exact); // 1.05e-5 at 1e3, 1.05e-7 at 1e4
        CHECK(relative_drift(r.out, "p_phi") < 1e-13);
        CHECK(relative_drift(r.out, "p_psi") < 1e-13);
        CHECK(relative_drift(r.out, "energy") < 1e-13);
        evals_per_period[k++] = rhs_evals(r.out) / 20;
    }
    // Measured: 241 and 136 evaluations per nutation period: the cost per unit time grows like
    // the spin (the nutation must be resolved), the cost per period does not.
    CHECK(evals_per_period[1] < 1.5 * evals_per_period[0]);
    CHECK(evals_per_period[1] > 0.5 * evals_per_period[0]);
}

TEST_CASE("fast spin 1e6: the Hamiltonian form's rounding noise no longer shrinks dop853's steps",
          "[extremes][fast_spin]") {
    // In (theta, p_phi, p_psi) the torque is a difference of terms of size p_psi^2: its rounding
    // noise is ~u p_psi^2. Under the per-component tolerance of before (each component relative
    // to itself) that noise was far above what p_theta was held to: at omega3 = 1e6 the
    // Hamiltonian form took 57x the Lagrangian form's evaluations. A momentum's error is now
    // relative to the length of the momentum vector (docs/integrators.md "What a tolerance
    // means"), which the noise stays below: over 20 nutation periods at rtol 1e-13, measured 629
    // evaluations in the Lagrangian form and 659 in the Hamiltonian form (1.05x; 1007 and 1370
    // held per step, before the error per unit step).
    const double period = 2 * pi / (0.5 * 1e6);
    double evals[2];
    int k = 0;
    for (const char* form : {"lagrangian", "hamiltonian"}) {
        const run_result r = simulate(
            "extremes_fast_spin_forms",
            fast_top(form, 1e6, 20 * period, 201, "method: dop853, rtol: 1e-13, atol: 1e-15"));
        INFO(form << "\n" << r.out << r.err);
        REQUIRE(r.status == 0);
        evals[k++] = rhs_evals(r.out);
    }
    CHECK(evals[1] < 2 * evals[0]); // measured 1.05
}

TEST_CASE("fast spin 1e6: RODAS4 damps the nutation, the implicit midpoint rule keeps it",
          "[extremes][fast_spin]") {
    // omega3 = 1e6 over t in [0, 1]: 80,000 nutation periods of 1.26e-5. Reference phi(1) from a
    // long-double dop853 run at rtol 1e-17 (bench/extremes/fast_spin_reference.cpp).
    // Measured: rosenbrock rtol 1e-6: 56 evaluations, phi(1) to 3.6e-7, the amplitude on
    // [1/2, 1] 6e-5 of the exact one; implicit midpoint h = 1e-3: 2169 evaluations, phi(1) to
    // 2.3e-6 (the nutation phase alone moves phi(1) by up to 2e-6), amplitude 1.0000; dop853 rtol
    // 1e-13 (per unit step, its share floored where the estimate is rounding): 4.48e6
    // evaluations, phi(1) to 3.5e-8, amplitude 0.72 (held per step: 2.16e6 evaluations, 3.6e-7,
    // and the nutation, 3.8e-12 rad, lost).
    const double phi_ref = 1.99999928866837587e-06, exact = exact_nutation(1e6);
    struct outcome {
        double phi_error, amplitude, evals;
    };
    const auto run = [&](const std::string& integrator) {
        const run_result r =
            simulate("extremes_stiff", fast_top("lagrangian", 1e6, 1, 1001, integrator));
        INFO(integrator << "\n" << r.out << r.err);
        REQUIRE(r.status == 0);
        const csv_table t = read_csv(scratch("extremes_stiff.csv"));
        const auto ts = t.values("t"), theta = t.values("theta");
        double lo = 1, hi = 0;
        for (std::size_t i = 0; i < ts.size(); ++i)
            if (ts[i] >= 0.5) lo = std::min(lo, theta[i]), hi = std::max(hi, theta[i]);
        CHECK(relative_drift(r.out, "p_phi") < 1e-12); // measured <= 2.5e-14
        CHECK(relative_drift(r.out, "p_psi") < 1e-12);
        return outcome{std::abs(t.values("phi").back() - phi_ref) / phi_ref, (hi - lo) / exact,
                       rhs_evals(r.out)};
    };
    const outcome rodas = run("method: rosenbrock, rtol: 1e-6, atol: 1e-8");
    const outcome midpoint = run("method: implicit_midpoint, step: 1e-3");
    const outcome dop853 = run("method: dop853, rtol: 1e-13, atol: 1e-15");
    CHECK(rodas.amplitude < 0.01);
    CHECK(rodas.phi_error < 3e-6);
    CHECK(midpoint.amplitude == Approx(1).margin(0.02));
    CHECK(midpoint.phi_error < 1e-5);
    CHECK(dop853.phi_error < 3.5e-7);           // measured 3.5e-8
    CHECK(midpoint.evals < dop853.evals / 200); // measured 2064x fewer
}

// ---- nearly equal moments, extreme ratios -------------------------------------------------------

TEST_CASE("nearly equal moments: I2 - I1 is exact in the body-form kernel", "[extremes][moments]") {
    // The emitted body form computes (p.I2 - p.I1) from the parameters: exact (Sterbenz) when
    // I2/2 <= I1 <= 2 I2, so omega3_dot = -(I2 - I1) omega1 omega2 / I3 keeps its full relative
    // accuracy however small I2 - I1 is. Long double on the same inputs is the reference.
    namespace m = rotgen::models::free_asymmetric_top_body;
    for (double eps : {1e-2, 1e-8, 1e-14}) {
        m::params<double> pd;
        m::params<long double> pl;
        pd.I1 = pl.I1 = 1.3;
        pd.I2 = 1.3 * (1 + eps);
        pl.I2 = pd.I2;
        pd.I3 = pl.I3 = 2.1;
        const double y[3] = {0.7, -1.1, 0.3};
        const long double yl[3] = {0.7, -1.1, 0.3};
        double f[3];
        long double fl[3];
        m::rhs(0.0, y, f, pd);
        m::rhs(0.0L, yl, fl, pl);
        INFO("eps " << eps);
        CHECK(std::abs(f[2] - fl[2]) <=
              4 * std::numeric_limits<double>::epsilon() * std::abs(fl[2]));
    }
}

TEST_CASE("nearly equal moments: the motion due to I1 != I2 is resolved down to eps = 1e-12",
          "[extremes][moments]") {
    // I = (1.3, 1.3 (1 + eps), 2.1): omega3 swings by ~eps. Measured (bench/extremes/moments.sh,
    // dop853 rtol 1e-12): max |omega - exact| 0.7e-14 ... 7e-14 in the body and Lagrangian forms
    // for eps = 1e-2 ... 1e-14 (9.5e-15 and 7.3e-15 at eps = 1e-12), against a data-rounding floor
    // of 8.7e-15: the error does not grow as eps shrinks. Margin: 1e-13 (10x at eps = 1e-12).
    const double eps = 1e-12;
    const std::array<double, 3> I{1.3, 1.3 * (1 + eps), 2.1};
    for (const char* form : {"body", "lagrangian"}) {
        const run_result r =
            simulate(std::string("extremes_moments_") + form, free_top_scene(form, I));
        INFO(form << "\n" << r.out << r.err);
        REQUIRE(r.status == 0);
        const free_top_check c =
            check_free_top(scratch(std::string("extremes_moments_") + form + ".csv"), I);
        CHECK(c.error < 1e-13);
        CHECK(c.exact_swing == Approx(1.01e-12).epsilon(0.02));
        CHECK(c.swing == Approx(c.exact_swing).epsilon(0.1)); // the eps-effect is there, to ~2%
    }
}

TEST_CASE("extreme ratios: moments scaled by 1e-6 and 1e6, and a needle 1 : 1e6",
          "[extremes][moments]") {
    // Euler's equations are homogeneous in I: the same omega(t) for (1, 1.5, 2) s. Measured in the
    // body form at rtol 1e-12: 7.7e-13 ... 8.2e-13 for s = 1e-6, 1, 1e6; the needle (1, 1e6,
    // 1e6 + 0.5) 2.0e-12 (its data-rounding floor: 3.7e-10). Margins: 3x.
    for (const auto& I : std::vector<std::array<double, 3>>{
             {1e-6, 1.5e-6, 2e-6}, {1e6, 1.5e6, 2e6}, {1, 1e6, 1000000.5}}) {
        const run_result r = simulate("extremes_ratios", free_top_scene("body", I));
        INFO(I[0] << " " << I[1] << " " << I[2] << "\n" << r.out << r.err);
        REQUIRE(r.status == 0);
        const free_top_check c = check_free_top(scratch("extremes_ratios.csv"), I);
        CHECK(c.error < (I[1] > 1e5 && I[0] < 10 ? 6e-12 : 2.5e-12));
    }
}

// ---- long runs
// -----------------------------------------------------------------------------------

TEST_CASE("long runs: 10^6 steps of rk4 drift, of the implicit midpoint rule do not",
          "[extremes][long_runs]") {
    // The heavy top (theta0 = 0.5, psi_dot = 30) in the Hamiltonian form, h = 0.01, t in [0, 1e4].
    // Measured (bench/extremes/long_runs.sh): energy drift after 1e4 / 1e5 / 1e6 steps
    // rk4 3.3e-9 / 3.3e-8 / 3.1e-7 (linear), implicit midpoint 6.2e-11 at all three (bounded);
    // p_phi and p_psi exactly constant (their derivatives are emitted as exact zeros).
    const auto drift = [](const std::string& method) {
        const run_result r = simulate(
            "extremes_long", "model: " + model_path("heavy_top") +
                                 "\nform: hamiltonian\ninitial: {theta: 0.5, psi_dot: 30, phi: 0, "
                                 "psi: 0, phi_dot: 0, theta_dot: 0}\n"
                                 "time: {end: 10000, samples: 1001}\nintegrator: {method: " +
                                 method + ", step: 0.01}\nrecord: [energy, p_phi, p_psi]\n");
        INFO(method << "\n" << r.out << r.err);
        REQUIRE(r.status == 0);
        CHECK(r.out.find("steps   1000000 accepted") != std::string::npos);
        const csv_table t = read_csv(scratch("extremes_long.csv"));
        const auto e = t.values("energy"), p_phi = t.values("p_phi"), p_psi = t.values("p_psi");
        std::array<double, 3> d{}; // after 1e4, 1e5, 1e6 steps
        double worst = 0;
        std::size_t moved = 0;
        for (std::size_t i = 0; i < e.size(); ++i) {
            worst = std::max(worst, std::abs(e[i] / e[0] - 1));
            if (i == 10) d[0] = worst;
            if (i == 100) d[1] = worst;
            moved += p_phi[i] != p_phi[0] || p_psi[i] != p_psi[0];
        }
        CHECK(moved == 0);
        d[2] = worst;
        return d;
    };
    const auto rk4 = drift("rk4"), midpoint = drift("implicit_midpoint");
    CHECK(rk4[2] > 5 * rk4[1]);
    CHECK(rk4[1] > 5 * rk4[0]);
    CHECK(rk4[2] < 1e-6);
    CHECK(midpoint[2] < 1.5 * midpoint[0]);
    CHECK(midpoint[2] < 2e-10);
}

// ---- precision
// -------------------------------------------------------------------------------------

namespace {
template <class T> std::pair<long double, rotgen::integration_result<T>> rk4_error(T h) {
    namespace m = rotgen::models::free_asymmetric_top_body;
    const rotgen::free_top_exact<long double> exact({1, 2, 3},
                                                    {1, (long double)T(0.1), (long double)T(0.5)});
    auto sys = ROTGEN_GENERATED_SYSTEM(m, T);
    rotgen::state_vector<T, decltype(sys)> y;
    y << T(1), T(0.1), T(0.5);
    std::vector<T> times(1001);
    for (std::size_t i = 0; i < times.size(); ++i)
        times[i] = T(100) * T(i) / T(1000);
    long double worst = 0;
    rotgen::rk4<T> method;
    method.step = h;
    const auto r = rotgen::integrate(sys, method, T(0), y, times, [&](T t, const auto& s) {
        const auto e = exact((long double)t);
        for (int j = 0; j < 3; ++j)
            worst = std::max(worst, std::abs((long double)s[j] - e[static_cast<std::size_t>(j)]));
    });
    return {worst, r};
}
} // namespace

TEST_CASE("precision: float, double and long double kernels on the same scene",
          "[extremes][precision]") {
    // The free asymmetric top I = (1, 2, 3), omega(0) = (1, 0.1, 0.5), t in [0, 100], rk4 with
    // h = 1e-3 (1e5 steps). Measured (bench/extremes/precision.sh): float 5.6e-5, double 2.3e-13,
    // long double 5.1e-14 (rk4's truncation error; double is at its rounding floor, which at
    // h = 1e-4 grows to 5.8e-13 while long double falls to 3.4e-16).
    const auto f = rk4_error<float>(1e-3f);
    const auto d = rk4_error<double>(1e-3);
    const auto l = rk4_error<long double>(1e-3L);
    REQUIRE(f.second.ok());
    REQUIRE(d.second.ok());
    REQUIRE(l.second.ok());
    CHECK(f.first > 1e-6);
    CHECK(f.first < 5e-4);
    CHECK(d.first < 1e-12);
    CHECK(l.first < 2e-13);
    CHECK(l.first < d.first);
    // Double at its rounding floor: 1e6 steps are no better than 1e5.
    CHECK(rk4_error<double>(1e-4).first > 0.5 * d.first);
    CHECK(rk4_error<long double>(1e-4L).first < 1e-15);
    // In float, fixed steps of 1e-4 stop where time can no longer hold them: h < 16 eps t at
    // t = 1e-4 / (16 * 2^-23) = 52.4.
    const auto stop = rk4_error<float>(1e-4f);
    CHECK(stop.second.code == rotgen::status::step_size_underflow);
    CHECK(stop.second.t == Approx(52).margin(1));
}
