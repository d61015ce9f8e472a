// The user-error sites of `rotgen bench` (generator/cli/bench_command.cpp, generator/bench/) that
// no other test pins, one table row each: exit 2, one line naming the command, the directory or
// the scene file with line and column, nothing on stdout and no output file written.
#include "error_sites.hpp"

#include <catch2/catch.hpp>

#include "bench/sources.hpp"

#include <cstdlib>
#include <filesystem>
#include <tuple>
#include <vector>

using namespace rotgen::test;
namespace fs = std::filesystem;

namespace {
const std::string scene =
    std::string(ROTGEN_SOURCE_DIR) + "/models/scenes/free_top_workprecision.yaml";

// No file at all under `dir` (bench may have made the directory itself).
bool holds_no_file(const fs::path& dir) {
    std::error_code ec;
    if (!fs::exists(dir, ec)) return true;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (!e.is_directory()) return false;
    return true;
}

// `rotgen bench SCENE -o DIR` run in the build tree: one error line, and no DIR made.
void check_bench_refuses(const std::string& scene_file, const std::string& line) {
    const scratch_dir out("bench_error_site_out");
    const run_result r =
        run_rotgen("bench " + scene_file + " -o '" + out.path.string() + "'", ROTGEN_BINARY_DIR);
    check_error_line(r, line);
    // every check of the input comes before the output directory is made: nothing is left
    CHECK(!fs::exists(out.path));
}
} // namespace

TEST_CASE("bench: bad --long-steps values are usage errors", "[bench][errors]") {
    const scratch_dir out("bench_error_site_steps");
    const std::string value = GENERATE(as<std::string>{}, "100000001", "1e6", "5x", "");
    INFO(value);
    const run_result r = run_rotgen("bench '" + scene + "' -o '" + out.path.string() +
                                    "' --long-steps '" + value + "'");
    check_error_line(r,
                     "rotgen bench: --long-steps needs a whole number of steps in [0, 1e8], got '" +
                         value + "'");
    CHECK(!fs::exists(out.path));
}

TEST_CASE("bench: output directories that cannot be used are named", "[bench][errors]") {
    const scratch_file file("bench_error_site_file", "keep\n");
    // GENERATE_COPY copies what it captures: the path, not the scratch file (whose copy would
    // remove the file when destroyed).
    const std::string file_path = file.path;
    using row = std::tuple<std::string, std::string>;
    // the -o argument, the problem after "DIR: "
    const auto [dir, problem] = GENERATE_COPY(table<std::string, std::string>({
        row{file_path, "the output path exists and is not a directory"},
        row{"/proc/x", "cannot create the output directory: No such file or directory"},
        row{"/proc", "cannot write: No such file or directory"},
    }));
    INFO(dir);
    check_error_line(run_rotgen("bench '" + scene + "' -o '" + dir + "'"), dir + ": " + problem);
    CHECK(read_file(file.path) == "keep\n");
    CHECK(!fs::exists("/proc/x"));
}

TEST_CASE("bench: an Euler-angle form at theta = 0 is refused at the initial key",
          "[bench][errors]") {
    const scratch_file file(
        "bench_error_site_lock.yaml",
        "model: " + model_path("heavy_top") +
            "\nform: lagrangian\ninitial: {phi: 0, theta: 0, psi: 0, omega1: 0.1, omega2: 0, "
            "omega3: 1}\ntime: {end: 1}\n");
    check_bench_refuses("bench_error_site_lock.yaml",
                        "bench_error_site_lock.yaml:3:10: initial theta is the gimbal-lock "
                        "singularity of the Euler-angle forms (sin theta = 0); use form: body");
}

TEST_CASE("bench: a cache directory that cannot be made is refused before any output",
          "[bench][errors]") {
    const scratch_dir out("bench_error_site_cache_out");
    // the cache is $ROTGEN_CACHE_DIR (bench's under it); /proc refuses new directories
    ::setenv("ROTGEN_CACHE_DIR", "/proc/nope", 1); // inherited by the child only
    const run_result r = run_rotgen("bench '" + scene + "' --quick -o '" + out.path.string() + "'");
    ::unsetenv("ROTGEN_CACHE_DIR");
    check_error_line(
        r, "/proc/nope: cannot use this folder as the kernel cache: No such file or directory; set "
           "ROTGEN_CACHE_DIR to a folder you can write");
    CHECK(!fs::exists(out.path)); // before this fix, plan.txt was written first
}

TEST_CASE("bench: the harness not found in any candidate tree is named with where it looked",
          "[bench][errors]") {
    // From `rotgen bench` this needs a build whose source tree has gone (the build's own tree is
    // always a candidate), so the search is called directly with trees that lack the harness.
    using rotgen::bench::bench_sources;
    const scratch_dir empty("bench_error_site_no_tree");
    fs::create_directories(empty.path / "runtime");
    const std::vector<bench_sources> candidates = {
        {"/proc/no/share/rotgen/bench/workprecision", "/proc/no/include/rotgen/runtime"},
        {empty.path / "bench/workprecision", empty.path / "runtime"}};
    try {
        rotgen::bench::first_complete(candidates);
        FAIL("no error");
    } catch (const rotgen::user_error& e) {
        CHECK(e.message() == "rotgen bench: cannot find the harness "
                             "(bench/workprecision/harness.hpp) and the runtime headers; looked "
                             "in /proc/no/share/rotgen/bench/workprecision, " +
                                 (empty.path / "bench/workprecision").string() +
                                 "; set ROTGEN_SOURCE_DIR to the rotgen source tree");
    }
    // the source tree itself is found
    const fs::path tree = ROTGEN_SOURCE_DIR;
    const bench_sources found = rotgen::bench::first_complete(
        {candidates[0], {tree / "bench/workprecision", tree / "runtime"}});
    CHECK(found.harness == tree / "bench/workprecision");
}

TEST_CASE("bench: a scene whose form the model cannot give says why", "[bench][errors]") {
    // phi appears in the potential: no cyclic coordinate, so no reduced form
    const scratch_file model("bench_error_site_phi.yaml",
                             "name: phitop\ninertia: [1, 2, 3]\npotential: 0.1*cos(phi)\n");
    const scratch_file file("bench_error_site_reduced.yaml",
                            "model: bench_error_site_phi.yaml\nform: reduced\ninitial: {phi: 0, "
                            "theta: 1, psi: 0, phi_dot: 0.1, theta_dot: 0, psi_dot: 1}\ntime: "
                            "{end: 1}\n");
    check_bench_refuses("bench_error_site_reduced.yaml",
                        "bench_error_site_reduced.yaml:1:1: the scene's form cannot be "
                        "benchmarked: the reduced form needs a cyclic coordinate, and model "
                        "'phitop' has none (damping, torques or the potential depend on every "
                        "angle or rate); use --form hamiltonian");
}
