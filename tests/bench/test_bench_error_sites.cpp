// The user-error sites of `rotgen bench` (generator/cli/bench_command.cpp, generator/bench/) that
// no other test pins, one table row each: exit 2, one line naming the command, the directory or
// the scene file with line and column, nothing on stdout and no output file written.
#include "error_sites.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <tuple>

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
    const scratch_dir out("bench_error_site_lock_out");
    const run_result r = run_rotgen(
        "bench bench_error_site_lock.yaml -o '" + out.path.string() + "'", ROTGEN_BINARY_DIR);
    check_error_line(r, "bench_error_site_lock.yaml:3:10: initial theta is the gimbal-lock "
                        "singularity of the Euler-angle forms (sin theta = 0); use form: body");
    // every check of the input comes before the output directory is made: nothing is left
    CHECK(!fs::exists(out.path));
}
