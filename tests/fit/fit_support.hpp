// rotgen fit's tests: synthetic measurements of a known truth, made with rotgen's own run (at the
// measurement times, exactly) and a seeded Gaussian noise.
#pragma once

#include "fit/data.hpp"
#include "fit/fit.hpp"
#include "fit/residuals.hpp"
#include "run/engine.hpp"
#include "scene/scene.hpp"
#include "support.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace rotgen::test {

// Deterministic normal deviates: Box-Muller on mt19937_64's fixed output sequence.
struct gauss {
    std::mt19937_64 g;
    explicit gauss(std::uint64_t seed) : g(seed) {}
    double uniform() { return (double((g() >> 11)) + 0.5) * 0x1.0p-53; }
    double operator()() {
        const double u = uniform(), v = uniform();
        return std::sqrt(-2 * std::log(u)) * std::cos(2 * 3.14159265358979323846 * v);
    }
};

struct synthetic {
    std::vector<std::string> names;
    std::vector<std::vector<double>> columns;
    std::string csv() const {
        std::string out;
        for (std::size_t c = 0; c < names.size(); ++c)
            out += (c ? "," : "") + names[c];
        out += "\n";
        for (std::size_t r = 0; r < columns[0].size(); ++r) {
            for (std::size_t c = 0; c < names.size(); ++c) {
                char buf[40];
                std::snprintf(buf, sizeof buf, "%.17g", columns[c][r]);
                out += (c ? "," : "") + std::string(buf);
            }
            out += "\n";
        }
        return out;
    }
};

// `n` times drawn uniformly in the scene's span (unsorted, as a log may hold them), the truth's
// omega1..3 with gyro noise and its attitude q0..q3 with a star tracker's (a rotation vector of
// independent components of deviation `tracker` applied in body axes); tracker 0: no attitude.
inline synthetic measure(const scene_spec& truth, std::uint64_t seed, std::size_t n, double gyro,
                         double tracker) {
    gauss noise(seed);
    std::vector<double> times;
    for (std::size_t i = 0; i < n; ++i)
        times.push_back(truth.t_start + (truth.t_end - truth.t_start) * noise.uniform());
    std::vector<double> sorted = times;
    std::sort(sorted.begin(), sorted.end());
    scene_spec s = with_records(truth, {"omega1", "omega2", "omega3", "q0", "q1", "q2", "q3"});
    s.sample_at = sorted;
    stage_timings timings;
    const rotgen::run_result r = run_scene(s, timings);
    const auto col = [&](const std::string& name) {
        return static_cast<std::size_t>(std::find(r.columns.begin(), r.columns.end(), name) -
                                        r.columns.begin()) +
               1;
    };
    synthetic d;
    d.names = {"t", "omega1", "omega2", "omega3"};
    if (tracker > 0) d.names.insert(d.names.end(), {"q0", "q1", "q2", "q3"});
    d.columns.resize(d.names.size());
    for (double t : times) {
        const auto& row = r.rows[static_cast<std::size_t>(
            std::lower_bound(sorted.begin(), sorted.end(), t) - sorted.begin())];
        d.columns[0].push_back(t);
        for (int k = 0; k < 3; ++k)
            d.columns[1 + k].push_back(row[col("omega" + std::to_string(k + 1))] + gyro * noise());
        if (tracker <= 0) continue;
        const Eigen::Quaterniond q(row[col("q0")], row[col("q1")], row[col("q2")], row[col("q3")]);
        const Eigen::Vector3d e(tracker * noise(), tracker * noise(), tracker * noise());
        const Eigen::Quaterniond m =
            q * Eigen::Quaterniond(Eigen::AngleAxisd(e.norm(), e.normalized()));
        for (int k = 0; k < 4; ++k)
            d.columns[4 + k].push_back(k == 0 ? m.w() : m.vec()[k - 1]);
    }
    return d;
}

// The scene with its parameter `name` set to `value`.
inline void set_parameter(scene_spec& s, const std::string& name, double value) {
    for (std::size_t i = 0; i < s.model.parameters.size(); ++i)
        if (s.model.parameters[i].name == name) s.parameters[i] = value;
}

inline double parameter_of(const scene_spec& s, const std::string& name) {
    for (std::size_t i = 0; i < s.model.parameters.size(); ++i)
        if (s.model.parameters[i].name == name) return s.parameters[i];
    return std::nan("");
}

inline fit_result fit_synthetic(const scene_spec& start, const synthetic& d,
                                const std::vector<std::string>& free, const std::string& sigma) {
    const measured_data data = measured_from_columns(d.names, d.columns, start, "synthetic");
    stage_timings timings;
    return fit_scene(start, data, free, sigma, 0, timings);
}

} // namespace rotgen::test
