// rotgen sweep: the files' lifecycle. The outcomes reach the writer in member order through a
// bounded window; what cannot be done is refused before any derivation; a folder never holds the
// files of two sweeps; an interrupted sweep keeps a journal that --resume finishes, byte for byte
// as an uninterrupted run. Interruptions come from the test hook ROTGEN_TEST_SWEEP_INTERRUPT
// (SIGTERM, or SIGINT, raised by the sweep itself once N chunks are in the journal): no timing.
#include "support.hpp"

#include "support/format.hpp"
#include "sweep/in_order.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>

using namespace rotgen;
using namespace rotgen::test;

namespace {

bool exists(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0;
}

std::string scratch(const std::string& name) {
    return std::string(ROTGEN_BINARY_DIR) + "/" + name;
}

// A fresh (missing) folder for a test's output.
std::string fresh(const std::string& name) {
    const std::string dir = scratch(name);
    std::filesystem::remove_all(dir);
    return dir;
}

// 21 members of the heavy top (7 tilts x 3 spins; the spin 2000 ones stop at max_steps), one
// member a journal chunk (a 64th of 21, at least 1).
std::string scene_text(int samples = 21) {
    return "model: " + model_path("heavy_top") +
           "\ninitial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}\n"
           "time: {end: 1, samples: " +
           std::to_string(samples) +
           "}\nintegrator: {method: dop853, rtol: 1e-10, atol: 1e-12, max_steps: 300}\n"
           "record: [theta, energy]\n"
           "sweep:\n  vary:\n    initial.theta: {from: 0.2, to: 1.4, count: 7}\n"
           "    initial.psi_dot: {values: [5, 30, 2000]}\n";
}

// `rotgen sweep` with the interruption hook set to `hook` (empty: none).
test::run_result sweep_with(const std::string& args, const std::string& hook = "") {
    if (!hook.empty()) ::setenv("ROTGEN_TEST_SWEEP_INTERRUPT", hook.c_str(), 1);
    test::run_result r = run_rotgen("sweep " + args);
    ::unsetenv("ROTGEN_TEST_SWEEP_INTERRUPT");
    return r;
}

std::vector<std::string> files_in(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

} // namespace

TEST_CASE("sweep: outcomes finished in any order reach the writer in member order, within the "
          "window",
          "[sweep][files]") {
    std::vector<std::size_t> written;
    in_order window(6, 3, [&](std::size_t m, member_outcome&& o) {
        CHECK(o.steps == 10 * m); // its own outcome
        written.push_back(m);
    });
    CHECK(window.fits(3));
    CHECK_FALSE(window.fits(4)); // member 3 waits until member 0 is written
    const auto outcome = [](std::size_t m) {
        member_outcome o;
        o.steps = 10 * m;
        return o;
    };
    window.deliver(2, outcome(2));
    window.deliver(1, outcome(1));
    CHECK(written.empty()); // 1 and 2 wait for 0
    CHECK_FALSE(window.fits(4));
    window.deliver(0, outcome(0));
    CHECK(written == std::vector<std::size_t>{0, 1, 2});
    CHECK(window.fits(6));
    CHECK(window.admit(6));
    window.deliver(4, outcome(4));
    window.deliver(5, outcome(5));
    window.deliver(3, outcome(3));
    CHECK(written == std::vector<std::size_t>{0, 1, 2, 3, 4, 5});
    window.stop();
    CHECK_FALSE(window.admit(6)); // a stopped window admits nothing
}

TEST_CASE("sweep: a grid of 1e16 members is refused at once, in little memory, before any "
          "derivation",
          "[sweep][files]") {
    const scratch_file scene("sweep_huge.yaml", scene_text());
    const std::string dir = fresh("sweep_huge_out");
    // Under 800 MB of address space: the two ranges of 1e8 values are never built (they were:
    // 1.6 GB, refused after 4.3 s, or std::bad_alloc here).
    const std::string err = scratch("sweep_huge.err");
    const int raw = std::system(("ulimit -v 800000; '" + std::string(ROTGEN_EXE) + "' sweep '" +
                                 scene.path + "' -o '" + dir +
                                 "' --timings --vary initial.theta=0.1:1.5:100000000 "
                                 "--vary initial.psi_dot=1:30:100000000 2>'" +
                                 err + "'")
                                    .c_str());
    CHECK(WEXITSTATUS(raw) == 2);
    CHECK(read_file(err) ==
          "rotgen: error: " + scene.path + ":7:3: the grid has 1e+16 members; at most 1e8\n");
    CHECK_FALSE(exists(dir));
    std::remove(err.c_str());
}

TEST_CASE("sweep: an output larger than the free disk space is refused with its estimate, "
          "before any derivation",
          "[sweep][files]") {
    // 1e8 members x 100,001 samples x 3 columns: 2.4e14 bytes of trajectories
    const scratch_file scene("sweep_disk.yaml", scene_text(100001));
    const std::string dir = fresh("sweep_disk_out");
    // ulimit -t: without the check, the sweep would start 1e8 members; it ends in 30 s of CPU
    const std::string err = scratch("sweep_disk.err");
    const int raw = std::system(("ulimit -t 30; '" + std::string(ROTGEN_EXE) + "' sweep '" +
                                 scene.path + "' -o '" + dir +
                                 "' --timings --trajectories --vary initial.psi_dot=30 --vary "
                                 "initial.theta=0.1:1.5:100000000 2>'" +
                                 err + "'")
                                    .c_str());
    CHECK(WEXITSTATUS(raw) == 2);
    const std::string line = read_file(err);
    CHECK(line.rfind("rotgen: error: " + dir +
                         ": the sweep would write about 2.4e+05 GB (100000000 members), more "
                         "than the ",
                     0) == 0);
    CHECK(line.find("GB free there\n") != std::string::npos);
    CHECK(line.find("derive") == std::string::npos); // no --timings line: nothing was derived
    CHECK_FALSE(exists(dir));
    std::remove(err.c_str());
}

TEST_CASE("sweep: a sweep into a folder of an earlier sweep replaces the whole set of files",
          "[sweep][files]") {
    const scratch_file scene("sweep_set.yaml", scene_text());
    const std::string dir = fresh("sweep_set_out");
    REQUIRE(sweep_with("'" + scene.path + "' -o '" + dir + "' -q --trajectories").status == 3);
    CHECK(files_in(dir) == std::vector<std::string>{"summary.csv", "trajectories.h5"});
    const test::run_result r =
        sweep_with("'" + scene.path + "' -o '" + dir + "' -q --vary initial.theta=0.3,0.4");
    CHECK(r.status == 3);
    // the earlier sweep's trajectories.h5 is gone with it: no mix of two sweeps
    CHECK(files_in(dir) == std::vector<std::string>{"summary.csv"});
    CHECK(text_lines(read_file(dir + "/summary.csv")).size() == 7); // the new sweep's 6 members
    std::filesystem::remove_all(dir);
}

TEST_CASE("sweep: interrupted before any member finished, it leaves nothing and says so",
          "[sweep][files]") {
    const scratch_file scene("sweep_nothing.yaml", scene_text());
    const std::string made = fresh("sweep_nothing_out");
    const auto [hook, status] = GENERATE(std::make_pair("0", 143), std::make_pair("0:INT", 130));
    test::run_result r =
        sweep_with("'" + scene.path + "' -o '" + made + "' -q --trajectories", hook);
    CHECK(r.status == status);
    CHECK(r.err == "rotgen: interrupted; nothing written\n");
    CHECK_FALSE(exists(made)); // the folder this run made is gone too
    // a folder that holds an earlier sweep's files keeps them, untouched
    REQUIRE(sweep_with("'" + scene.path + "' -o '" + made + "' -q").status == 3);
    const std::string before = read_file(made + "/summary.csv");
    r = sweep_with("'" + scene.path + "' -o '" + made + "' -q --trajectories", hook);
    CHECK(r.status == status);
    CHECK(files_in(made) == std::vector<std::string>{"summary.csv"});
    CHECK(read_file(made + "/summary.csv") == before);
    std::filesystem::remove_all(made);
}

TEST_CASE("sweep: an interrupted sweep keeps the journal of its finished members, and --resume "
          "finishes it byte for byte",
          "[sweep][files]") {
    const scratch_file scene("sweep_resume.yaml", scene_text());
    const std::string whole = fresh("sweep_resume_whole"), dir = fresh("sweep_resume_out");
    const std::string jobs = GENERATE("1", "2");
    const std::string args = "'" + scene.path + "' -q --trajectories -j " + jobs + " -o ";
    REQUIRE(sweep_with(args + "'" + whole + "'").status == 3);
    test::run_result r = sweep_with(args + "'" + dir + "'", "5");
    CHECK(r.status == 143);
    CHECK(r.err == "rotgen: interrupted; kept the journal " + dir +
                       "/summary.partial.csv (5 members): add --resume to the same command to "
                       "finish\n");
    CHECK(files_in(dir) == std::vector<std::string>{"summary.partial.csv", "sweep.partial",
                                                    "trajectories.partial.h5"});
    // the journal's rows are the first five of the whole run's, whole
    const auto all = text_lines(read_file(whole + "/summary.csv"));
    CHECK(text_lines(read_file(dir + "/summary.partial.csv")) ==
          std::vector<std::string>(all.begin(), all.begin() + 6));
    // a plain rerun is refused, and so is --resume with other options
    r = sweep_with(args + "'" + dir + "'");
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: " + dir +
                       "/summary.partial.csv: the journal of an interrupted sweep (5 members "
                       "finished): add --resume to finish it, or remove the folder's *.partial* "
                       "files to start again\n");
    r = sweep_with(args + "'" + dir + "' --resume --vary initial.theta=0.2,0.3");
    CHECK(r.status == 2);
    CHECK(r.err.find("sweep.partial: this journal is of another scene or other options") !=
          std::string::npos);
    // interrupted again while resuming, then finished
    r = sweep_with(args + "'" + dir + "' --resume", "4:INT");
    CHECK(r.status == 130);
    CHECK(r.err.find("(9 members)") != std::string::npos);
    r = sweep_with(args.substr(0, args.find(" -q ")) + args.substr(args.find(" -q ") + 3) + "'" +
                   dir + "' --resume"); // with the summary: the 12 members it ran, not 21
    CHECK(r.status == 3);
    CHECK((r.out + r.err)
              .find("  resumed after the journal's 9 members (the lines below: the 12 "
                    "run now)\n") != std::string::npos);
    CHECK(files_in(dir) == std::vector<std::string>{"summary.csv", "trajectories.h5"});
    CHECK(read_file(dir + "/summary.csv") == read_file(whole + "/summary.csv"));
    CHECK(read_file(dir + "/trajectories.h5") == read_file(whole + "/trajectories.h5"));
    std::filesystem::remove_all(whole);
    std::filesystem::remove_all(dir);
}

TEST_CASE("the files' numbers are printf's 17 significant digits, for any double", "[sweep]") {
    const auto printf17 = [](double x) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", x);
        return std::string(buf);
    };
    const double edge[] = {0.0,
                           -0.0,
                           1.0,
                           0.1,
                           -2.5e-7,
                           1e300,
                           5e-324,
                           2.2250738585072014e-308,
                           123456789012345678.0,
                           1e16,
                           1e17,
                           9.999999999999999e22,
                           std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()};
    for (double x : edge)
        CHECK(format_number(x) == printf17(x));
    std::mt19937_64 bits(7);
    int differ = 0;
    for (int i = 0; i < 100000; ++i) {
        const std::uint64_t b = bits();
        double x;
        std::memcpy(&x, &b, sizeof x);
        if (!std::isnan(x) && format_number(x) != printf17(x)) ++differ;
    }
    CHECK(differ == 0);
    CHECK(format_number(std::nan("")) == "nan"); // no sign: "-nan" would mean nothing
}
