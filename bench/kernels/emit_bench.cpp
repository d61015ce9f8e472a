// Generated kernels, timed: ns per rhs and per jacobian call for every shipped model and form, the
// Lagrangian strategies (explicit vs solve) for speed and for accuracy near theta = 0, and the same
// equations written by hand (sin/cos once, as a careful person would).
//
//   kernel_bench [PREFIX]     prints Markdown tables; writes PREFIX.md and PREFIX.csv if given
//
// Timing: 256 random states (theta in [0.3, pi - 0.3]) evaluated in turn, repeated until a run
// takes >= 20 ms; the median of 7 runs. Accuracy: relative max-norm error of q_ddot in double
// against the same kernel in 50-digit arithmetic (boost::multiprecision::cpp_bin_float_50).
#include "bench_units.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using clock_type = std::chrono::steady_clock;
volatile double sink = 0;

constexpr double pi = 3.141592653589793;

template <class Names>
std::vector<std::vector<double>> random_states(const Names& names, std::size_t count,
                                               unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> angle(0, 2 * pi), polar(0.3, pi - 0.3), rate(-2, 2);
    std::normal_distribution<double> gauss;
    std::vector<std::vector<double>> states;
    for (std::size_t k = 0; k < count; ++k) {
        std::vector<double> y;
        double q2 = 0;
        for (const char* name : names) {
            const std::string s = name;
            if (s == "theta")
                y.push_back(polar(rng));
            else if (s == "phi" || s == "psi")
                y.push_back(angle(rng));
            else if (s[0] == 'q' && s.size() == 2)
                y.push_back(gauss(rng)), q2 += y.back() * y.back();
            else
                y.push_back(rate(rng));
        }
        if (q2 > 0)
            for (int i = 0; i < 4; ++i)
                y[static_cast<std::size_t>(i)] /= std::sqrt(q2);
        states.push_back(y);
    }
    return states;
}

// ns per call of f(y, out) over the states.
template <class F>
double time_per_call(const std::vector<std::vector<double>>& states, std::size_t out_size, F f) {
    std::vector<double> out(out_size);
    const auto run = [&](long reps) {
        const auto t0 = clock_type::now();
        for (long r = 0; r < reps; ++r)
            for (const auto& y : states) {
                f(y.data(), out.data());
                sink = sink + out[out_size - 1];
            }
        return std::chrono::duration<double>(clock_type::now() - t0).count();
    };
    long reps = 1;
    while (run(reps) < 0.02)
        reps *= 2;
    std::vector<double> times;
    for (int i = 0; i < 7; ++i)
        times.push_back(run(reps));
    std::sort(times.begin(), times.end());
    return times[3] / static_cast<double>(reps * static_cast<long>(states.size())) * 1e9;
}

// "rhs: 96 -> 37 (" in the generated header's comment.
std::pair<long, long> ops_of(const std::string& unit, const std::string& function) {
    std::ifstream in(std::string(ROTGEN_BENCH_GENERATED) + "/" + unit + ".hpp");
    std::string line;
    const std::string key = "//   " + function + ": ";
    while (std::getline(in, line))
        if (line.rfind(key, 0) == 0) {
            long before = 0, after = 0;
            std::sscanf(line.c_str() + key.size(), "%ld -> %ld", &before, &after);
            return {before, after};
        }
    return {-1, -1};
}

// ---- hand-written references ----

// The heavy symmetric top from (5.73): Euler-Lagrange equations with p_phi, p_psi conserved.
struct heavy_top_hand {
    double I1 = 1.0, I3 = 0.5, Mgh = 1.0 * 9.81 * 0.1;
    void operator()(const double* y, double* f) const {
        const double st = std::sin(y[1]), ct = std::cos(y[1]);
        const double phid = y[3], thetad = y[4], psid = y[5];
        const double w3 = phid * ct + psid;
        f[0] = phid, f[1] = thetad, f[2] = psid;
        f[4] = (I1 * phid * phid * st * ct - I3 * w3 * phid * st + Mgh * st) / I1;
        f[3] = (I3 * w3 - 2 * I1 * phid * ct) * thetad / (I1 * st);
        f[5] = -(f[3] * ct - phid * st * thetad);
    }
};

// Any tensor, gravity: omega = J q_dot, omega_dot = I^{-1}(r x (-M g e) - omega x I omega),
// q_ddot = J^{-1}(omega_dot - J_dot q_dot). I and I^{-1} precomputed.
struct euler_hand {
    double I[3][3], Iinv[3][3], Mg, r[3];
    explicit euler_hand(const double (&tensor)[3][3], double mass_g, const double (&com)[3])
        : Mg(mass_g) {
        for (int i = 0; i < 3; ++i) {
            r[i] = com[i];
            for (int j = 0; j < 3; ++j)
                I[i][j] = tensor[i][j];
        }
        const double det = I[0][0] * (I[1][1] * I[2][2] - I[1][2] * I[2][1]) -
                           I[0][1] * (I[1][0] * I[2][2] - I[1][2] * I[2][0]) +
                           I[0][2] * (I[1][0] * I[2][1] - I[1][1] * I[2][0]);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
                Iinv[i][j] = (I[r0][c0] * I[r1][c1] - I[r0][c1] * I[r1][c0]) / det;
            }
    }
    void operator()(const double* y, double* f) const {
        const double st = std::sin(y[1]), ct = std::cos(y[1]), sp = std::sin(y[2]),
                     cp = std::cos(y[2]);
        const double phid = y[3], thetad = y[4], psid = y[5];
        const double w[3] = {phid * st * sp + thetad * cp, phid * st * cp - thetad * sp,
                             phid * ct + psid};
        double l[3];
        for (int i = 0; i < 3; ++i)
            l[i] = I[i][0] * w[0] + I[i][1] * w[1] + I[i][2] * w[2];
        const double e[3] = {st * sp, st * cp, ct};
        const double b[3] = {-Mg * (r[1] * e[2] - r[2] * e[1]) - (w[1] * l[2] - w[2] * l[1]),
                             -Mg * (r[2] * e[0] - r[0] * e[2]) - (w[2] * l[0] - w[0] * l[2]),
                             -Mg * (r[0] * e[1] - r[1] * e[0]) - (w[0] * l[1] - w[1] * l[0])};
        const double jdot[3] = {phid * (ct * thetad * sp + st * cp * psid) - thetad * sp * psid,
                                phid * (ct * thetad * cp - st * sp * psid) - thetad * cp * psid,
                                -phid * st * thetad};
        double a[3];
        for (int i = 0; i < 3; ++i)
            a[i] = Iinv[i][0] * b[0] + Iinv[i][1] * b[1] + Iinv[i][2] * b[2] - jdot[i];
        f[0] = phid, f[1] = thetad, f[2] = psid;
        f[3] = (a[0] * sp + a[1] * cp) / st;
        f[4] = a[0] * cp - a[1] * sp;
        f[5] = a[2] - f[3] * ct;
    }
};

struct row {
    std::string model, unit, form;
    std::size_t n;
    double rhs_ns, jac_ns;
    std::pair<long, long> rhs_ops, jac_ops;
};

// ---- accuracy near theta = 0 ----

using big = boost::multiprecision::cpp_bin_float_50;

template <class Kernel> double accuracy(Kernel kernel, double theta, std::mt19937& rng) {
    std::uniform_real_distribution<double> angle(0, 2 * pi), rate(-2, 2);
    double worst = 0;
    for (int k = 0; k < 200; ++k) {
        const double y[6] = {angle(rng), theta, angle(rng), rate(rng), rate(rng), rate(rng)};
        big yb[6], fb[6];
        double f[6];
        for (int i = 0; i < 6; ++i)
            yb[i] = y[i];
        kernel(y, f, yb, fb);
        big scale = 0, err = 0;
        for (int i = 3; i < 6; ++i) {
            scale = std::max(scale, big(abs(fb[i])));
            err = std::max(err, big(abs(fb[i] - big(f[i]))));
        }
        worst = std::max(worst, static_cast<double>(err / scale));
    }
    return worst;
}

#define ROTGEN_ACCURACY_KERNEL(u)                                                                  \
    [](const double* y, double* f, const big* yb, big* fb) {                                       \
        rotgen::models::u::rhs(0.0, y, f, rotgen::models::u::params<double>{});                    \
        rotgen::models::u::rhs(big(0), yb, fb, rotgen::models::u::params<big>{});                  \
    }

} // namespace

int main(int argc, char** argv) {
    std::vector<row> rows;
#define ROTGEN_BENCH_ROW(model, u, form_name)                                                      \
    {                                                                                              \
        namespace ns = rotgen::models::u;                                                          \
        const auto states = random_states(ns::state_names, 256, 42);                               \
        const ns::params<double> p{};                                                              \
        const double rhs_ns = time_per_call(                                                       \
            states, ns::state_size, [&p](const double* y, double* f) { ns::rhs(0.5, y, f, p); });  \
        const double jac_ns =                                                                      \
            time_per_call(states, ns::state_size * ns::state_size,                                 \
                          [&p](const double* y, double* J) { ns::jacobian(0.5, y, J, p); });       \
        rows.push_back({#model, #u, #form_name, ns::state_size, rhs_ns, jac_ns, ops_of(#u, "rhs"), \
                        ops_of(#u, "jacobian")});                                                  \
        std::fprintf(stderr, "%s done\n", #u);                                                     \
    }
    ROTGEN_BENCH_UNITS(ROTGEN_BENCH_ROW)

    // hand-written references
    struct hand_row {
        std::string what;
        double ns;
    };
    std::vector<hand_row> hand;
    {
        const auto states = random_states(rotgen::models::heavy_top::state_names, 256, 42);
        const heavy_top_hand h;
        hand.push_back(
            {"heavy_top, hand-written (5.73) Euler-Lagrange", time_per_call(states, 6, h)});
        const double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 0.5}};
        const double com[3] = {0, 0, 0.1};
        const euler_hand e(I, 9.81, com);
        hand.push_back(
            {"heavy_top, hand-written Euler's equations + J^{-1}", time_per_call(states, 6, e)});
        const double If[3][3] = {{2.0, -0.3, 0.2}, {-0.3, 2.5, -0.1}, {0.2, -0.1, 1.5}};
        const double comf[3] = {0.05, -0.02, 0.15};
        const euler_hand ef(If, 1.2 * 9.81, comf);
        hand.push_back({"full_tensor_top, hand-written Euler's equations + J^{-1}",
                        time_per_call(states, 6, ef)});
    }

    // explicit vs solve near theta = 0 and pi
    struct accuracy_row {
        std::string model;
        double theta, explicit_error, solve_error;
    };
    std::vector<accuracy_row> acc;
    for (double theta : {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, pi - 1e-4, pi - 1e-8}) {
        std::mt19937 r1(1), r2(1), r3(1), r4(1);
        acc.push_back({"heavy_top", theta, accuracy(ROTGEN_ACCURACY_KERNEL(heavy_top), theta, r1),
                       accuracy(ROTGEN_ACCURACY_KERNEL(heavy_top_solve), theta, r2)});
        acc.push_back({"full_tensor_top", theta,
                       accuracy(ROTGEN_ACCURACY_KERNEL(full_tensor_top), theta, r3),
                       accuracy(ROTGEN_ACCURACY_KERNEL(full_tensor_top_solve), theta, r4)});
    }

    std::ostringstream md, csv;
    md << "| model | unit | form | n | rhs ops (before -> after) | jacobian ops | rhs ns | "
          "jacobian ns | jac/rhs |\n"
       << "|---|---|---|---|---|---|---|---|---|\n";
    csv << "model,unit,form,n,rhs_ops_before,rhs_ops_after,jacobian_ops_before,jacobian_ops_after,"
           "rhs_ns,jacobian_ns\n";
    char buf[512];
    for (const row& r : rows) {
        std::snprintf(buf, sizeof buf,
                      "| %s | %s | %s | %zu | %ld -> %ld | %ld -> %ld | %.1f | %.1f | %.2f |\n",
                      r.model.c_str(), r.unit.c_str(), r.form.c_str(), r.n, r.rhs_ops.first,
                      r.rhs_ops.second, r.jac_ops.first, r.jac_ops.second, r.rhs_ns, r.jac_ns,
                      r.jac_ns / r.rhs_ns);
        md << buf;
        std::snprintf(buf, sizeof buf, "%s,%s,%s,%zu,%ld,%ld,%ld,%ld,%.2f,%.2f\n", r.model.c_str(),
                      r.unit.c_str(), r.form.c_str(), r.n, r.rhs_ops.first, r.rhs_ops.second,
                      r.jac_ops.first, r.jac_ops.second, r.rhs_ns, r.jac_ns);
        csv << buf;
    }
    md << "\n| hand-written reference | rhs ns |\n|---|---|\n";
    for (const auto& h : hand) {
        std::snprintf(buf, sizeof buf, "| %s | %.1f |\n", h.what.c_str(), h.ns);
        md << buf;
    }
    md << "\n| model | theta | explicit: max rel. error of q_ddot | solve: max rel. error "
          "|\n|---|---|---|---|\n";
    for (const auto& a : acc) {
        char theta[64];
        if (a.theta > 1)
            std::snprintf(theta, sizeof theta, "pi - %.0e", pi - a.theta);
        else
            std::snprintf(theta, sizeof theta, "%.0e", a.theta);
        std::snprintf(buf, sizeof buf, "| %s | %s | %.2e | %.2e |\n", a.model.c_str(), theta,
                      a.explicit_error, a.solve_error);
        md << buf;
    }
    std::fputs(md.str().c_str(), stdout);
    if (argc > 1) {
        std::ofstream(std::string(argv[1]) + ".md") << md.str();
        std::ofstream(std::string(argv[1]) + ".csv") << csv.str();
    }
    return 0;
}
