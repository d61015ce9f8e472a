// Issues 17 and 18: `rotgen bench SCENE` plans the split methods (split2, split4, split6) and the
// Taylor method beside the others when the model admits them, by the checks `rotgen simulate`
// makes; when it does not, the plan says why with simulate's own refusal. The plans are made
// without compiling anything (bench_plan_text); `rotgen bench --quick` end to end, with the
// errors of these rows, is in test_bench.cpp.
#include "bench/bench.hpp"
#include "support.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace rotgen::test;

namespace {

struct planned {
    std::map<std::string, std::vector<double>> tols;  // rotgen's runs by method: tolerances
    std::map<std::string, std::vector<int>> variants; // and variants
    std::vector<std::string> left_out;
    std::vector<double> moments;
};

planned plan_of(const std::string& scene, bool quick) {
    ::setenv("ROTGEN_CACHE_DIR", (std::string(ROTGEN_BINARY_DIR) + "/bench-cache").c_str(), 1);
    rotgen::bench_options o;
    o.scene = std::string(ROTGEN_SOURCE_DIR) + "/models/scenes/" + scene;
    o.quick = quick;
    planned p;
    std::istringstream in(rotgen::bench_plan_text(o));
    for (std::string line; std::getline(in, line);) {
        std::istringstream l(line);
        std::string what, peer, method, scalar;
        int v = 0;
        double tol = 0, step = 0;
        l >> what;
        if (what == "run" && l >> v >> peer >> method >> scalar >> tol >> step &&
            peer == "rotgen" && scalar == "double") {
            p.tols[method].push_back(tol);
            p.variants[method].push_back(v);
        } else if (what == "moments") {
            for (double m; l >> m;)
                p.moments.push_back(m);
        } else if (line.rfind("# left out: ", 0) == 0) {
            p.left_out.push_back(line.substr(12));
        }
    }
    return p;
}

bool all_equal(const std::vector<int>& v, int x) {
    for (int y : v)
        if (y != x) return false;
    return !v.empty();
}

} // namespace

TEST_CASE("bench plan: the heavy top runs split2, split4, split6 and taylor over a sweep",
          "[bench]") {
    const planned p = plan_of("heavy_top_nutation.yaml", false);
    CHECK(p.left_out.empty());
    // I = (I1, I1, I3) = (1, 1, 0.5) of models/heavy_top.yaml: diagonal, so split runs
    CHECK(p.moments == std::vector<double>{1, 1, 0.5});
    // split2 down to 1e-9 (its step goes as rtol^(1/2)), split4 and split6 to 1e-13 like DOP853
    CHECK(p.tols.at("split2") == std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9});
    CHECK(p.tols.at("split4").size() == 11);
    CHECK(p.tols.at("split6") == p.tols.at("split4"));
    CHECK(p.tols.at("split4").back() == 1e-13);
    CHECK(p.tols.at("taylor").size() == 13);
    CHECK(p.tols.at("taylor").back() == 1e-15);
    // the split methods on one variant, not the main (the scene's form is lagrangian): the body
    // form with the quaternion; taylor on the main variant, the scene's form as simulate runs it
    const int sv = p.variants.at("split2").front();
    CHECK(sv != 0);
    for (const char* m : {"split2", "split4", "split6"})
        CHECK(all_equal(p.variants.at(m), sv));
    CHECK(all_equal(p.variants.at("taylor"), 0));
}

TEST_CASE("bench plan: the free top (quick) runs split and taylor too", "[bench]") {
    const planned p = plan_of("free_top_workprecision.yaml", true);
    CHECK(p.left_out.empty());
    CHECK(p.moments == std::vector<double>{1, 2, 3});
    for (const char* m : {"split2", "split4", "split6", "taylor"})
        CHECK(p.tols.count(m) == 1);
    CHECK(p.tols.at("taylor") == p.tols.at("split4"));
}

TEST_CASE("bench plan: the damped top leaves split out with simulate's reason", "[bench]") {
    const planned p = plan_of("damped_top.yaml", true);
    CHECK(p.tols.count("split2") + p.tols.count("split4") + p.tols.count("split6") == 0);
    CHECK(p.moments.empty());
    CHECK(p.tols.count("taylor") == 1); // sin, cos and the drive's sin(t) have recurrences
    REQUIRE(p.left_out.size() == 1);
    const std::string prefix = "split2, split4, split6: ";
    REQUIRE(p.left_out[0].rfind(prefix, 0) == 0);
    const std::string reason = p.left_out[0].substr(prefix.size());
    CHECK(reason.find("damping depends on the rates") != std::string::npos);
    // the same scene run by `rotgen simulate` with split2 is refused with this very text
    std::string scene =
        read_file(std::string(ROTGEN_SOURCE_DIR) + "/models/scenes/damped_top.yaml");
    const std::string model = "model: ../damped_driven_top.yaml";
    REQUIRE(scene.find(model) != std::string::npos);
    scene.replace(scene.find(model), model.size(),
                  "model: " + std::string(ROTGEN_SOURCE_DIR) + "/models/damped_driven_top.yaml");
    const std::string integrator = "integrator: {method: dopri5, rtol: 1e-8, atol: 1e-10}";
    REQUIRE(scene.find(integrator) != std::string::npos);
    scene.replace(scene.find(integrator), integrator.size(),
                  "integrator: {method: split2, step: 0.01}");
    const scratch_file file("bench_plan_damped_split2.yaml", scene);
    const std::string csv = std::string(ROTGEN_BINARY_DIR) + "/bench_plan_damped_split2.csv";
    const run_result r = run_rotgen("simulate '" + file.path + "' -o '" + csv + "'");
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find(": " + reason + "\n") != std::string::npos);
}
