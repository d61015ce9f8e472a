// Splitting on the exact free flow against DOP853 at fast spin (issue 17; bench/split/split.sh
// writes bench/results/split.md from this program's table).
//
// Bodies: the heavy symmetric top I = (1, 1, 0.5) and an asymmetric one I = (1, 1.2, 0.5), centre
// of mass on the body z axis with M g h = 0.981, tilted θ = 0.5 rad, released with φ̇ = θ̇ = 0 and
// ψ̇ = spin (ω = (0, 0, spin), (5.30)), t = 0..10. Error: the angle of the rotation between the
// attitude at t = 10 and a reference (DOP853 in long double at rtol 1e-17). Cost: wall time of one
// run (median of 5 timings, each of enough repetitions to last 20 ms). DOP853 runs the body form
// (quaternion, ω) with the same torque, at rtol = atol from 1e-4 to 1e-13; the split methods under
// error control at the same rtol = atol. Both are calibrated as `rotgen simulate` calibrates them
// (step_control.hpp: calibrate() with the body form's layout, the quaternion an attitude and ω
// one vector), so that rtol means the error at the samples for each. The cost at an error target
// is that of the cheapest run from which every tighter rtol also meets it.
//   split_bench            prints one line per body, spin, method and configuration
//   split_bench long       split2 over 10^7 steps (h = 0.01, spin 10): the largest energy error
//                          and p_phi change in each decade of steps, per body
#include "calibrated.hpp"
#include "integrate/integrate.hpp"
#include "rotation.hpp"
#include "steppers/dop853.hpp"
#include "steppers/split_doubling.hpp"
#include "steppers/splitting.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace rotgen;

namespace {

constexpr double t_end = 10, mgh = 0.981;

template <class T> auto heavy_body(const std::array<double, 3>& in) {
    return make_split_system<T>({T(in[0]), T(in[1]), T(in[2])},
                                gravity_torque<T>{{T(0), T(0), T(mgh)}});
}

template <class T> Eigen::Matrix<T, 7, 1> start(double spin) {
    const Eigen::Quaterniond q = quaternion_from_euler(0.0, 0.5, 0.0);
    Eigen::Matrix<T, 7, 1> y;
    y << T(q.w()), T(q.x()), T(q.y()), T(q.z()), T(0), T(0), T(spin);
    return y;
}

Eigen::Quaterniond attitude(const Eigen::Matrix<double, 7, 1>& y) {
    return Eigen::Quaterniond(y[0], y[1], y[2], y[3]).normalized();
}

Eigen::Quaterniond reference(const std::array<double, 3>& in, double spin) {
    using ld = long double;
    auto sys = heavy_body<ld>(in);
    Eigen::Matrix<ld, 7, 1> y = start<ld>(spin);
    dop853<ld> m(1e-17L, 1e-17L);
    m.max_steps = 100000000;
    integrate(sys, m, 0.0L, y, ld(t_end));
    return attitude(y.cast<double>());
}

// Seconds for one call of run(), median of 5 timings of enough repetitions to last 20 ms.
template <class F> double seconds(F run) {
    using clock = std::chrono::steady_clock;
    int reps = 1;
    for (;;) {
        const auto t0 = clock::now();
        for (int i = 0; i < reps; ++i)
            run();
        const double s = std::chrono::duration<double>(clock::now() - t0).count();
        if (s > 0.02 || reps > (1 << 20)) break;
        reps *= 2;
    }
    std::vector<double> t;
    for (int k = 0; k < 5; ++k) {
        const auto t0 = clock::now();
        for (int i = 0; i < reps; ++i)
            run();
        t.push_back(std::chrono::duration<double>(clock::now() - t0).count() / reps);
    }
    std::sort(t.begin(), t.end());
    return t[2];
}

double angle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
    return orientation_error<double>(matrix_from_quaternion(a), matrix_from_quaternion(b));
}

template <class M>
double measure(const char* body, const std::array<double, 3>& in, double spin,
               const Eigen::Quaterniond& ref, M method, double knob) {
    const auto sys = heavy_body<double>(in);
    Eigen::Matrix<double, 7, 1> y = start<double>(spin);
    const auto r = integrate(sys, method, 0.0, y, t_end);
    if (r.code != status::ok) return 1;
    const double err = angle(attitude(y), ref);
    const double s = seconds([&] {
        Eigen::Matrix<double, 7, 1> z = start<double>(spin);
        integrate(sys, method, 0.0, z, t_end);
    });
    std::printf("%s %g %s %.3g %zu %.4g %.4g\n", body, spin, method.name().c_str(), knob,
                r.stats.steps, err, s);
    return err;
}

// The method under error control (steppers/split_doubling.hpp) at rtol = atol = 1e-4, 1e-5, ...
// until its error is past the targets.
template <int P>
void split_runs(const char* body, const std::array<double, 3>& in, double spin,
                const Eigen::Quaterniond& ref) {
    for (double tol = 1e-4; tol >= 1e-13; tol /= 10) {
        const auto m = calibrated(split_controlled<double, P>(tol, tol));
        if (measure(body, in, spin, ref, m, tol) < 1e-11) break; // past the targets
    }
}

double energy(const std::array<double, 3>& in, const Eigen::Matrix<double, 7, 1>& y) {
    return (in[0] * y[4] * y[4] + in[1] * y[5] * y[5] + in[2] * y[6] * y[6]) / 2 +
           mgh * (1 - 2 * (y[1] * y[1] + y[2] * y[2]));
}

double p_phi(const std::array<double, 3>& in, const Eigen::Matrix<double, 7, 1>& y) {
    const Eigen::Vector3d m(in[0] * y[4], in[1] * y[5], in[2] * y[6]);
    return (attitude(y) * m)[2];
}

// split2, h = 0.01, 10^7 steps; energy and p_phi sampled every 1000 steps.
void long_run(const char* body, const std::array<double, 3>& in) {
    const auto sys = heavy_body<double>(in);
    Eigen::Matrix<double, 7, 1> y = start<double>(10);
    const double e0 = energy(in, y), p0 = p_phi(in, y), h = 0.01;
    std::vector<double> times;
    for (int i = 1; i <= 10000; ++i)
        times.push_back(1000.0 * i * h);
    std::array<double, 5> de{}, dp{}; // decades of steps: up to 1e3, 1e4, ..., 1e7
    split2<double> m;
    m.step = h;
    const auto t0 = std::chrono::steady_clock::now();
    integrate(sys, m, 0.0, y, times, [&](double t, const auto& s) {
        const int d = std::max(0, int(std::ceil(std::log10(t / h) - 1e-9)) - 3);
        de[d] = std::max(de[d], std::abs(energy(in, s) - e0) / e0);
        dp[d] = std::max(dp[d], std::abs(p_phi(in, s) - p0) / std::abs(p0));
    });
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (int d = 0; d < 5; ++d)
        std::printf("%s 1e%d %.3g %.3g %.3g\n", body, d + 3, de[d], dp[d], s);
}

} // namespace

int main(int argc, char** argv) {
    if (argc > 1 && std::string(argv[1]) == "long") {
        long_run("symmetric", {1, 1, 0.5});
        long_run("asymmetric", {1, 1.2, 0.5});
        return 0;
    }
    const std::array<std::pair<const char*, std::array<double, 3>>, 2> bodies = {
        {{"symmetric", {1, 1, 0.5}}, {"asymmetric", {1, 1.2, 0.5}}}};
    // optional: one body and spin only (split_bench asymmetric 1000), for before/after runs
    const std::string only_body = argc > 2 ? argv[1] : "";
    const double only_spin = argc > 2 ? std::atof(argv[2]) : 0;
    std::printf("body spin method knob steps error seconds\n");
    for (const auto& [name, in] : bodies)
        for (double spin : {10.0, 100.0, 1000.0, 10000.0}) {
            if (!only_body.empty() && (only_body != name || only_spin != spin)) continue;
            const Eigen::Quaterniond ref = reference(in, spin);
            for (double tol = 1e-4; tol >= 1e-13; tol /= 10) {
                const auto m = calibrated(dop853<double>(tol, tol));
                measure(name, in, spin, ref, m, tol);
            }
            split_runs<2>(name, in, spin, ref);
            split_runs<4>(name, in, spin, ref);
            split_runs<6>(name, in, spin, ref);
            std::fflush(stdout);
        }
}
