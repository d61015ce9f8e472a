// What a tolerance means (issue 50, point 1; docs/integrators.md "What a tolerance means"): one
// error norm for every adaptive method (the attitude in radians, the rates relative to their
// vector: runtime/step_control.hpp, error_layout) and each method's calibration, so that the
// largest error over the samples (attitude angle, |Δω| / |ω|) is near rtol for every method.
// Two scenes: a fast heavy top (bench/proportionality/fast_top.yaml: C/A 0.3, spin 1e3, its psi
// grows to 1e4 rad) and the shipped nutating top; every adaptive method at rtol 1e-6 and 1e-9,
// against taylor at 1e-15. The table bench/results/proportionality.md has all of 1e-5 … 1e-10.
#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <regex>

using namespace rotgen::test;

namespace {

std::string scratch(const std::string& name) {
    return std::string(ROTGEN_BINARY_DIR) + "/" + name;
}

// The scene file at `path` (under the source tree) run with `integrator`, recording the attitude
// and body ω; `name` names the scratch files (unique per test case).
csv_table run_scene(const std::string& path, const std::string& integrator,
                    const std::string& name) {
    std::string text = read_file(std::string(ROTGEN_SOURCE_DIR) + "/" + path);
    const std::string dir = std::string(ROTGEN_SOURCE_DIR) + "/" + path.substr(0, path.rfind('/'));
    text = std::regex_replace(text, std::regex("\nmodel: "), "\nmodel: " + dir + "/");
    text =
        std::regex_replace(text, std::regex("\nintegrator:[^\n]*"), "\nintegrator: " + integrator);
    text = std::regex_replace(text, std::regex("\nrecord:[^\n]*"),
                              "\nrecord: [q0, q1, q2, q3, omega1, omega2, omega3]");
    const scratch_file scene(name + ".yaml", text);
    const run_result r =
        run_rotgen("simulate '" + scene.path + "' -q -o '" + scratch(name + ".csv") + "'");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    return read_csv(scratch(name + ".csv"));
}

// The largest over the samples of the attitude angle between a and b and of |Δω| / |ω_b|.
double sample_error(const csv_table& a, const csv_table& b) {
    REQUIRE(a.rows.size() == b.rows.size());
    double worst = 0;
    for (std::size_t i = 0; i < a.rows.size(); ++i) {
        double minus = 0, plus = 0, dw = 0, w = 0;
        for (const char* c : {"q0", "q1", "q2", "q3"}) {
            minus += std::pow(a.values(c)[i] - b.values(c)[i], 2);
            plus += std::pow(a.values(c)[i] + b.values(c)[i], 2);
        }
        for (const char* c : {"omega1", "omega2", "omega3"}) {
            dw += std::pow(a.values(c)[i] - b.values(c)[i], 2);
            w += std::pow(b.values(c)[i], 2);
        }
        const double angle = 4 * std::asin(std::sqrt(std::min(minus, plus)) / 2);
        worst = std::max({worst, angle, std::sqrt(dw / w)});
    }
    return worst;
}

// error ÷ rtol of each method at rtol 1e-6 and 1e-9 on the scene at `path`.
std::map<std::string, std::array<double, 2>> ratios(const std::string& path,
                                                    const std::string& name) {
    const csv_table ref =
        run_scene(path, "{method: taylor, rtol: 1e-15, atol: 1e-15}", name + "_ref");
    std::map<std::string, std::array<double, 2>> out;
    for (const char* m : {"dop853", "dopri5", "rosenbrock", "taylor", "split2", "split4", "split6"})
        for (int k = 0; k < 2; ++k) {
            const double rtol = k == 0 ? 1e-6 : 1e-9;
            char spec[96];
            std::snprintf(spec, sizeof spec, "{method: %s, rtol: %g, atol: %g}", m, rtol, rtol);
            out[m][std::size_t(k)] = sample_error(run_scene(path, spec, name), ref) / rtol;
        }
    return out;
}

// Each method's error ÷ rtol within 10x of what was observed (both ways), its two tolerances'
// ratios within the 30x of each other, and the methods within 100x of each other at
// each tolerance (observed: the largest quotient, beside the bound).
void check_meaning(const std::map<std::string, std::array<double, 2>>& r,
                   const std::map<std::string, std::array<double, 2>>& observed,
                   const std::array<double, 2>& observed_agreement) {
    for (const auto& [method, seen] : observed)
        for (std::size_t k = 0; k < 2; ++k) {
            const double got = r.at(method)[k];
            INFO(method << (k == 0 ? " rtol 1e-6" : " rtol 1e-9") << ": error/rtol " << got
                        << ", observed " << seen[k]);
            CHECK(got < 10 * seen[k]);
            CHECK(got > seen[k] / 10);
        }
    for (const auto& [method, v] : r) {
        INFO(method << ": error/rtol " << v[0] << " at 1e-6, " << v[1] << " at 1e-9");
        CHECK(std::max(v[0], v[1]) / std::min(v[0], v[1]) < 30);
    }
    for (std::size_t k = 0; k < 2; ++k) {
        double lo = 1e300, hi = 0;
        for (const auto& [method, v] : r)
            lo = std::min(lo, v[k]), hi = std::max(hi, v[k]);
        INFO((k == 0 ? "rtol 1e-6" : "rtol 1e-9")
             << ": methods within " << hi / lo << ", observed " << observed_agreement[k]);
        CHECK(hi / lo < 100);
    }
}

} // namespace

TEST_CASE("rtol means the error at the samples for every method on a fast heavy top",
          "[simulate][tolerance]") {
    const auto r = ratios("bench/proportionality/fast_top.yaml", "tolerance_fast_top");
    // observed error ÷ rtol at 1e-6, 1e-9 (bench/results/proportionality.md)
    check_meaning(r,
                  {{"dop853", {2.42, 2.57}},
                   {"dopri5", {2.86, 2.4}},
                   {"rosenbrock", {3.25, 3.06}},
                   {"taylor", {1.25, 0.794}},
                   {"split2", {0.216, 0.258}},
                   {"split4", {0.106, 0.0864}},
                   {"split6", {0.0514, 0.0376}}},
                  {63, 81});
}

TEST_CASE("rtol means the error at the samples for every method on the nutating top",
          "[simulate][tolerance]") {
    const auto r = ratios("models/scenes/heavy_top_nutation.yaml", "tolerance_nutation");
    check_meaning(r,
                  {{"dop853", {0.161, 0.16}},
                   {"dopri5", {0.158, 0.155}},
                   {"rosenbrock", {0.2, 0.199}},
                   {"taylor", {0.0531, 0.0255}},
                   {"split2", {1.97, 1.95}},
                   {"split4", {0.292, 0.256}},
                   {"split6", {1.18, 1.22}}},
                  {37, 76});
}
