// Issue 24, "documentation claims that are false today": what the documentation (docs/scenes.md)
// and the shipped scenes say, checked against what rotgen does.
#include "files_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

using namespace rotgen::test;
namespace fs = std::filesystem;

TEST_CASE("Euler-angle rates at theta = 0 are written nan, as the scene reference says",
          "[simulate][claims]") {
    const std::string dir = fresh_folder("claims_theta0");
    // a spin about the vertical: theta stays exactly 0, where only phi_dot + psi_dot is defined
    std::ofstream(dir + "/spin.yaml")
        << "model: " << model_path("heavy_top") << "\nform: body\n"
        << "initial: {phi: 0, theta: 0, psi: 0, omega1: 0, omega2: 0, omega3: 30}\n"
        << "time: {end: 0.1, samples: 2}\nrecord: [theta, phi_dot, psi_dot, omega3]\n";
    const run_result r = run_rotgen("simulate spin.yaml -o -", dir);
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(without_provenance(r.out) ==
          "t,theta,phi_dot,psi_dot,omega3\n0,0,nan,nan,30\n0.10000000000000001,0,nan,"
          "nan,30\n");
    CHECK(r.err.find("4 recorded values are not finite (inf or nan)") != std::string::npos);
    std::ifstream readme(std::string(ROTGEN_SOURCE_DIR) + "/docs/scenes.md");
    const std::string text((std::istreambuf_iterator<char>(readme)),
                           std::istreambuf_iterator<char>());
    CHECK(text.find("as `nan`, and the summary says so") != std::string::npos);
}

TEST_CASE("simulate --events on a scene without events writes the header and says why it is empty",
          "[simulate][claims]") {
    const std::string dir = fresh_folder("claims_no_events");
    write_top_scene(dir + "/top.yaml");
    const run_result r = run_rotgen("simulate top.yaml -o out.csv --events ev.csv", dir);
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(without_provenance(read_file(dir + "/ev.csv")) == "event,t,phase,theta\n");
    CHECK(r.out.find("wrote   ev.csv (0 events; the scene has no events:)\n") != std::string::npos);
}

TEST_CASE("the shipped dumbbell pendulum passes near the pole and changes chart, as it says",
          "[simulate][claims]") {
    const std::string dir = fresh_folder("claims_dumbbell");
    const run_result r = run_rotgen("simulate '" + std::string(ROTGEN_SOURCE_DIR) +
                                        "/models/scenes/dumbbell_pendulum.yaml' "
                                        "-o out.csv",
                                    dir);
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("  chart   ") != std::string::npos);
    CHECK(r.out.find("rotor_x") != std::string::npos);
    const csv_table t = read_csv(dir + "/out.csv");
    double closest = 1;
    for (double theta : t.values("theta"))
        closest = std::min(closest, std::abs(std::sin(theta)));
    CHECK(closest < 0.1); // the switch threshold; observed 0.05 (the scene's comment)
}

TEST_CASE("the scene reference's list of shipped scenes names every scene in models/scenes",
          "[simulate][claims]") {
    std::ifstream readme(std::string(ROTGEN_SOURCE_DIR) + "/docs/scenes.md");
    const std::string text((std::istreambuf_iterator<char>(readme)),
                           std::istreambuf_iterator<char>());
    const std::size_t from = text.find("**Shipped scenes**");
    REQUIRE(from != std::string::npos);
    const std::string list = text.substr(from, text.find("\n\n", from) - from);
    std::set<std::string> missing;
    for (const auto& e : fs::directory_iterator(std::string(ROTGEN_SOURCE_DIR) + "/models/scenes"))
        if (e.path().extension() == ".yaml" &&
            list.find("`" + e.path().stem().string() + "`") == std::string::npos)
            missing.insert(e.path().stem().string());
    CHECK(missing.empty());
}
