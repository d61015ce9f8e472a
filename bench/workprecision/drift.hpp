// rotgen bench — the long runs: the relative energy error over time of one method on one variant
// (the `drift` directives of the plan; harness.hpp).
#pragma once

#include "run_record.hpp"
#include "runners.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace rotgen::bench {

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

} // namespace rotgen::bench
