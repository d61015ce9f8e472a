// The write-failure sites of `rotgen emit` (generator/cli/emit_command.cpp) and of the atomic
// output file (generator/support/atomic_file.cpp), pinned exactly: exit 2, one line naming the
// path, nothing on stdout, nothing created. (/proc refuses new entries, even to root.)
#include "error_sites.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <tuple>

using namespace rotgen::test;

TEST_CASE("cli: emit into a directory it cannot create or write names the directory",
          "[cli][errors]") {
    using row = std::tuple<std::string, std::string>;
    // the -o argument, the problem after "DIR: "
    const auto [dir, problem] = GENERATE(table<std::string, std::string>({
        row{"/proc/x", "cannot create the output directory: No such file or directory"},
        row{"/proc/x/y", "cannot create the output directory: No such file or directory"},
        row{"/proc", "cannot write: No such file or directory"},
    }));
    INFO(dir);
    // the directory when it cannot be made; the header's path when it cannot be written
    const std::string where = dir == "/proc" ? "/proc/heavy_top.hpp" : dir;
    check_error_line(run_rotgen("emit '" + model_path("heavy_top") + "' -o '" + dir + "'"),
                     where + ": " + problem);
}

TEST_CASE("cli: emit of a model it refuses creates no output directory", "[cli][errors]") {
    // (under /proc nothing could be created anyway: here the directory could be)
    const std::string dir = std::string(ROTGEN_BINARY_DIR) + "/emit_refused";
    std::filesystem::remove_all(dir);
    const std::string model = std::string(ROTGEN_BINARY_DIR) + "/emit_refused_model.yaml";
    std::ofstream(model) << "name: refused\ninertia: [1, 1]\n";
    const run_result r = run_rotgen("emit '" + model + "' -o '" + dir + "'");
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.err.rfind("rotgen: error: " + model + ":2:", 0) == 0);
    CHECK(!std::filesystem::exists(dir));
}

TEST_CASE("cli: simulate into a file it cannot create names the file", "[cli][errors]") {
    const std::string scene = std::string(ROTGEN_SOURCE_DIR) + "/models/scenes/damped_top.yaml";
    check_error_line(run_rotgen("simulate '" + scene + "' -o /proc/x/a.csv"),
                     "/proc/x/a.csv: cannot write: No such file or directory");
}
