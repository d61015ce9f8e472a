// Issue 46, "no silent loss": every write is checked, the standard output's too, and exit 2 means
// nothing was written.
//   2. A full standard output (/dev/full) is exit 2 with one line, never "wrote standard output";
//      a reader that went away stays exit 141, quietly (test_signals.cpp).
//   3. A command with several outputs commits them together: one that fails (a --view or --events
//      to /dev/full) leaves no other file behind.
//   8. `rotgen help --help`, `rotgen help help`, `rotgen --help` and `rotgen help simulate` print
//      help and exit 0.
// The /dev/full cases are skipped (with a warning saying so) where the platform has no /dev/full.
#include "files_support.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>

using namespace rotgen::test;
namespace fs = std::filesystem;

namespace {

// Whether /dev/full is there: a character device whose writes fail with ENOSPC (a warning says
// that the test is skipped where it is not).
bool have_dev_full() {
    struct stat st {};
    if (::stat("/dev/full", &st) == 0 && S_ISCHR(st.st_mode)) return true;
    WARN("skipped: this platform has no /dev/full");
    return false;
}

// `rotgen ARGS` in `dir` with its standard output sent to `out` (a path), standard error kept.
run_result run_to(const std::string& args, const std::string& out, const std::string& dir) {
    const std::string err = dir + "/stderr.txt";
    const std::string cmd = "cd '" + dir + "' && '" + std::string(ROTGEN_EXE) + "' " + args +
                            " >'" + out + "' 2>'" + err + "' </dev/null";
    const int raw = std::system(cmd.c_str());
    run_result r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.err = read_file(err);
    fs::remove(err);
    return r;
}

const std::string full_line = "rotgen: error: standard output: cannot write: No space left on "
                              "device\n";

} // namespace

TEST_CASE("a full standard output is exit 2 with one line for simulate, inspect and emit",
          "[cli][outputs]") {
    if (!have_dev_full()) return; // WARNed by have_dev_full
    const std::string dir = fresh_folder("outputs_stdout_full");
    write_top_scene(dir + "/top.yaml");
    const std::string model = "'" + model_path("heavy_top") + "'";
    for (const std::string& args :
         std::vector<std::string>{"simulate top.yaml -o - -q", "inspect " + model,
                                  "emit " + model + " -o -", "simulate top.yaml -o out.csv"}) {
        INFO(args);
        const run_result r = run_to(args, "/dev/full", dir);
        CHECK(r.status == 2);
        CHECK(r.err == full_line);   // never "rotgen: wrote standard output"
        CHECK(entries_in(dir) == 1); // the scene: out.csv (whose summary failed) did not appear
    }
    // the same commands into a file: exit 0 (what makes them fail above is the full device)
    const run_result ok = run_to("inspect " + model, dir + "/inspect.txt", dir);
    CHECK(ok.status == 0);
    CHECK(read_file(dir + "/inspect.txt").size() > 1000); // observed 3,9xx bytes
}

// A sweep writes its folder as it goes (its journal is what --resume continues): a standard output
// that fails after it finished cannot take the folder back, so the run is one that could not
// finish: status 3, and the line says the files are complete and kept.
TEST_CASE("a full standard output after a sweep is exit 3 with its folder complete",
          "[cli][outputs]") {
    if (!have_dev_full()) return; // WARNed by have_dev_full
    const std::string dir = fresh_folder("outputs_sweep_stdout_full");
    write_top_scene(dir + "/top.yaml");
    const run_result r =
        run_to("sweep top.yaml -o out -j 1 --vary initial.theta=0.4:0.6:3", "/dev/full", dir);
    CHECK(r.status == 3);
    CHECK(r.err == "rotgen: error: standard output: cannot write: No space left on device after "
                   "the sweep finished: the files it wrote in its folder are complete and kept\n");
    const std::string summary = read_file(dir + "/out/summary.csv");
    CHECK(std::count(summary.begin(), summary.end(), '\n') == 4); // the header and 3 members
    // with its standard output in a file, the same sweep is exit 0
    const run_result ok = run_to("sweep top.yaml -o out2 -j 1 --vary initial.theta=0.4:0.6:3",
                                 dir + "/sweep.txt", dir);
    CHECK(ok.status == 0);
}
TEST_CASE("emit -o DIR with a full standard output leaves no header", "[cli][outputs]") {
    if (!have_dev_full()) return; // WARNed by have_dev_full
    const std::string dir = fresh_folder("outputs_emit_full");
    const run_result r = run_to("emit '" + model_path("heavy_top") + "' -o hdr", "/dev/full", dir);
    CHECK(r.status == 2);
    CHECK(r.err == full_line);
    CHECK_FALSE(fs::exists(dir + "/hdr")); // its "wrote" line failed first: no header, no folder
    // a folder that was there stays, with what it held
    fs::create_directories(dir + "/kept");
    write_top_scene(dir + "/kept/top.yaml");
    const run_result k =
        run_to("emit '" + model_path("heavy_top") + "' -o kept/a/b", "/dev/full", dir);
    CHECK(k.status == 2);
    CHECK_FALSE(fs::exists(dir + "/kept/a"));
    CHECK(fs::exists(dir + "/kept/top.yaml"));
}

TEST_CASE("exit 2 leaves no file: simulate -o good.csv with --view or --events on /dev/full",
          "[cli][outputs]") {
    if (!have_dev_full()) return; // WARNed by have_dev_full
    const std::string dir = fresh_folder("outputs_all_or_none");
    const std::string scenes = std::string(ROTGEN_SOURCE_DIR) + "/models/scenes/";
    write_top_scene(dir + "/ok.yaml");
    struct attempt {
        std::string args, error;
    };
    for (const attempt& a :
         {attempt{"simulate ok.yaml -o good.csv --view /dev/full", "/dev/full"},
          attempt{"simulate '" + scenes + "falling_top.yaml' -o good.csv --events /dev/full",
                  "/dev/full"},
          attempt{"simulate ok.yaml -o good.csv --plot p.png --view /dev/full", "/dev/full"}}) {
        INFO(a.args);
        const run_result r = run_rotgen(a.args, dir);
        CHECK(r.status == 2);
        CHECK(r.err == "rotgen: error: " + a.error + ": cannot write: No space left on device\n");
        CHECK_FALSE(fs::exists(dir + "/good.csv"));
        CHECK_FALSE(fs::exists(dir + "/p.png"));
        CHECK(entries_in(dir) == 1); // ok.yaml: no output, no temporary
    }
    // the same run with a writable page: every output appears
    const run_result r = run_rotgen("simulate ok.yaml -o good.csv --view page.html -q", dir);
    CHECK(r.status == 0);
    CHECK(fs::exists(dir + "/good.csv"));
    CHECK(fs::exists(dir + "/page.html"));
}

TEST_CASE("help: rotgen help --help, help help, --help and help simulate exit 0", "[cli]") {
    const run_result usage = run_rotgen("--help");
    REQUIRE(usage.status == 0);
    CHECK(usage.out.rfind("usage: rotgen <command>", 0) == 0);
    for (const std::string args : {"help --help", "help help", "help -h", "help"}) {
        INFO(args);
        const run_result r = run_rotgen(args);
        CHECK(r.status == 0);
        CHECK(r.err.empty());
        CHECK(r.out == usage.out);
    }
    const run_result simulate = run_rotgen("help simulate");
    CHECK(simulate.status == 0);
    CHECK(simulate.out == run_rotgen("simulate --help").out);
    CHECK(simulate.out.rfind("usage: rotgen simulate ", 0) == 0);
}
