// Issue 24, "a file is never destroyed, and a run's outputs never collide": every output of one
// run is distinct from every other and from every input, refused with exit 2 before any work;
// names derived from a stream output (-, a device, a FIFO); emit -o -; exit 3 keeps the events;
// an unusable kernel cache is a user error, not an internal one.
#include "error_sites.hpp"
#include "files_support.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>

using namespace rotgen::test;
namespace fs = std::filesystem;

namespace {

std::string fresh_dir(const std::string& name) {
    return fresh_folder("contract_" + name);
}

// An environment variable set for the children this test starts, unset at scope exit.
struct env_var {
    std::string name;
    env_var(std::string n, const std::string& value) : name(std::move(n)) {
        ::setenv(name.c_str(), value.c_str(), 1);
    }
    ~env_var() { ::unsetenv(name.c_str()); }
};

} // namespace

TEST_CASE("simulate refuses two outputs that are one file, before any work, naming both options",
          "[simulate][contract]") {
    const std::string dir = fresh_dir("collide");
    write_top_scene(dir + "/top.yaml");
    std::ofstream(dir + "/a.csv") << "keep\n";
    fs::create_symlink("a.csv", dir + "/link.csv");
    fs::create_directories(dir + "/sub");
    const std::vector<std::pair<std::string, std::string>> cases{
        {"-o a.csv --events a.csv", "a.csv: -o and --events"},
        {"-o a.csv --events link.csv", "link.csv: -o and --events"},
        {"-o ./a.csv --events a.csv", "a.csv: -o and --events"},
        {"--events top.csv", "top.csv: the default output and --events"},
        {"-o a.png --plot a.png", "a.png: -o and --plot"},
        {"-o n.csv --plot sub/../n.csv", "sub/../n.csv: -o and --plot"},
        {"-o b.csv --events b.partial.csv", "b.partial.csv: --events and the partial rows' file "
                                            "(exit 3)"}};
    // the test hook ends a run that gets past the checks with SIGTERM (143) when it starts to
    // derive: a refusal (2) came before any work
    const env_var hook("ROTGEN_TEST_SIGNAL", "TERM:derive");
    for (const auto& [options, problem] : cases) {
        INFO(options);
        check_error_line(run_rotgen("simulate top.yaml " + options, dir),
                         problem + " name the same file; give each its own name");
    }
    CHECK(run_rotgen("simulate top.yaml -o c.csv --events d.csv", dir).status == 143);
    CHECK(read_file(dir + "/a.csv") == "keep\n");
    CHECK(fs::is_symlink(dir + "/link.csv"));
    CHECK(entries_in(dir) == 4); // top.yaml, a.csv, link.csv, sub
}

TEST_CASE("an output that is an input is refused by every command that writes files",
          "[simulate][contract]") {
    const std::string dir = fresh_dir("inputs");
    const std::string scene = write_top_scene(dir + "/trajectories.h5");
    const std::string text = read_file(scene);
    const env_var hook("ROTGEN_TEST_SIGNAL", "TERM:derive");
    // simulate: through a hard link to the scene
    fs::create_hard_link(scene, dir + "/hard.csv");
    check_error_line(run_rotgen("simulate trajectories.h5 -o hard.csv", dir),
                     "hard.csv: -o would write over the scene 'trajectories.h5', a file this "
                     "command reads");
    // sweep: its trajectories file is the scene (before this check: overwritten, exit 0)
    check_error_line(run_rotgen("sweep trajectories.h5 -o . --vary initial.theta=0.4:0.5:2 "
                                "--trajectories -q",
                                dir),
                     "./trajectories.h5: --trajectories would write over the scene "
                     "'trajectories.h5', a file this command reads");
    // bench: one of the files of its folder is the scene
    fs::copy_file(scene, dir + "/results.md");
    check_error_line(run_rotgen("bench results.md -o . --quick", dir),
                     "./results.md: -o . (results.md) would write over the scene 'results.md', "
                     "a file this command reads");
    // emit: the header is the model
    fs::copy_file(model_path("heavy_top"), dir + "/heavy_top.hpp");
    check_error_line(run_rotgen("emit heavy_top.hpp -o .", dir),
                     "./heavy_top.hpp: -o . would write over the model 'heavy_top.hpp', a file "
                     "this command reads");
    CHECK(read_file(scene) == text);
    CHECK(read_file(dir + "/results.md") == text);
    CHECK(read_file(dir + "/heavy_top.hpp") == read_file(model_path("heavy_top")));
    CHECK(entries_in(dir) == 4);
}

TEST_CASE("no file is derived from a stream output: the events go beside the scene's name",
          "[simulate][contract]") {
    const std::string dir = fresh_dir("stream");
    write_top_scene(dir + "/top.yaml",
                    "events: [{name: early, when: t - 0.25, direction: rising}]\n");
    run_result r = run_rotgen("simulate top.yaml -o /dev/null", dir);
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("wrote   top.events.csv (1 events)") != std::string::npos);
    const bool beside_device = fs::exists("/dev/null.events.csv");
    fs::remove("/dev/null.events.csv"); // what the run wrote before this rule
    CHECK_FALSE(beside_device);
    const csv_table events = read_csv(dir + "/top.events.csv");
    REQUIRE(events.rows.size() == 1);
    CHECK(std::abs(events.rows[0][1] - 0.25) < 1e-12); // the zero of t - 0.25; observed exact
    // -o /dev/stdout into a pipe writes into the pipe, as -o - does; the summary goes to stderr
    std::ofstream(dir + "/pipe.sh") << "'" << ROTGEN_EXE
                                    << "' simulate top.yaml -o /dev/stdout --events e.csv "
                                       "2>err.txt | cat >pipe.txt\necho ${PIPESTATUS[0]} "
                                       ">status.txt\n";
    REQUIRE(std::system(("cd '" + dir + "' && bash pipe.sh").c_str()) == 0);
    CHECK(read_file(dir + "/status.txt") == "0\n");
    const std::string piped = read_file(dir + "/pipe.txt");
    CHECK(without_provenance(piped).rfind("t,theta\n0,0.5\n", 0) == 0);
    CHECK(std::count(piped.begin(), piped.end(), '\n') == 13); // provenance, header, 11 samples
    CHECK(read_file(dir + "/err.txt").find("wrote   /dev/stdout (11 samples)") !=
          std::string::npos);
}

TEST_CASE("emit -o - writes the header to standard output, never a folder named -",
          "[emit][contract]") {
    const std::string dir = fresh_dir("emit_stdout");
    const run_result piped = run_rotgen("emit '" + model_path("heavy_top") + "' -o -", dir);
    INFO(piped.err);
    REQUIRE(piped.status == 0);
    CHECK_FALSE(fs::exists(dir + "/-"));
    CHECK(piped.err.rfind("rotgen: wrote standard output (heavy_top.hpp; operations: ", 0) == 0);
    const run_result filed = run_rotgen("emit '" + model_path("heavy_top") + "' -o out", dir);
    REQUIRE(filed.status == 0);
    // the same header as -o out but for the command that regenerates it
    std::string header = read_file(dir + "/out/heavy_top.hpp");
    const std::size_t at = header.find(" -o out --form ");
    REQUIRE(at != std::string::npos);
    header.replace(at, 8, " -o - ");
    CHECK(piped.out == header);
}

TEST_CASE("a run that stops early keeps its events beside its partial rows (exit 3)",
          "[simulate][contract]") {
    const std::string dir = fresh_dir("partial_events");
    write_top_scene(dir + "/top.yaml",
                    "integrator: {method: rk4, step: 1e-3, max_steps: 300}\n"
                    "events: [{name: early, when: t - 0.1, direction: rising}]\n");
    const run_result r = run_rotgen("simulate top.yaml -o out.csv", dir);
    INFO(r.out << r.err);
    REQUIRE(r.status == 3);
    CHECK(r.err.find("the 4 samples computed so far are in out.partial.csv and its 1 events in "
                     "out.partial.events.csv\n") != std::string::npos);
    CHECK(r.out.find("wrote   out.partial.events.csv (1 events, partial)") != std::string::npos);
    const csv_table rows = read_csv(dir + "/out.partial.csv");
    CHECK(rows.rows.size() == 4); // t = 0, 0.1, 0.2, 0.3: 300 steps of 1e-3
    const csv_table events = read_csv(dir + "/out.partial.events.csv");
    REQUIRE(events.rows.size() == 1);
    CHECK(std::abs(events.rows[0][1] - 0.1) < 1e-12); // the zero of t - 0.1; observed exact
    CHECK(events.rows[0][3] == Approx(rows.rows[1][1]).epsilon(1e-6)); // theta at t = 0.1
    CHECK(entries_in(dir) == 3);
}

TEST_CASE("a kernel cache that cannot be used is a user error naming it and ROTGEN_CACHE_DIR",
          "[simulate][contract]") {
    const std::string dir = fresh_dir("cache");
    write_top_scene(dir + "/top.yaml");
    std::ofstream(dir + "/file") << "a regular file\n";
    const std::string advice = "; set ROTGEN_CACHE_DIR to a folder you can write";
    {
        const env_var cache("ROTGEN_CACHE_DIR", dir + "/file/cache");
        check_error_line(run_rotgen("simulate top.yaml -o out.csv", dir),
                         dir +
                             "/file/cache: cannot use this folder as the kernel cache: Not a "
                             "directory" +
                             advice);
    }
    {
        const env_var cache("ROTGEN_CACHE_DIR", dir + "/file");
        check_error_line(run_rotgen("simulate top.yaml -o out.csv", dir),
                         dir +
                             "/file: cannot use this folder as the kernel cache: it is not a "
                             "folder" +
                             advice);
    }
    { // the default, under a HOME that is not a folder
        const std::string home = std::getenv("HOME") ? std::getenv("HOME") : "";
        const std::string xdg = std::getenv("XDG_CACHE_HOME") ? std::getenv("XDG_CACHE_HOME") : "";
        const char* given = std::getenv("ROTGEN_CACHE_DIR");
        const std::string cache = given ? given : "";
        ::unsetenv("XDG_CACHE_HOME");
        ::unsetenv("ROTGEN_CACHE_DIR");
        ::setenv("HOME", (dir + "/file").c_str(), 1);
        const run_result r = run_rotgen("simulate top.yaml -o out.csv", dir);
        ::setenv("HOME", home.c_str(), 1);
        if (!xdg.empty()) ::setenv("XDG_CACHE_HOME", xdg.c_str(), 1);
        if (given) ::setenv("ROTGEN_CACHE_DIR", cache.c_str(), 1);
        check_error_line(r, dir +
                                "/file/.cache/rotgen: cannot use this folder as the kernel "
                                "cache: Not a directory" +
                                advice);
    }
    CHECK(entries_in(dir) == 2);
}
