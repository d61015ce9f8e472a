// rotgen simulate's output contract: where the samples go (-o FILE, -o -, the default name, a
// symlink, a device), what is refused (an input as output, an unknown plot format), a run that
// cannot finish (exit 3, rows in <output>.partial.csv). Interrupted runs:
// tests/cli/test_signals.cpp.
#include "files_support.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace rotgen::test;
namespace fs = std::filesystem;

namespace {

std::string scratch_dir(const std::string& name) {
    return fresh_folder("outputs_" + name);
}

// A short heavy-top scene in `dir`, returning its path.
std::string heavy_scene(const std::string& dir, const std::string& extra = "") {
    return write_top_scene(dir + "/top.yaml", extra);
}

} // namespace

TEST_CASE("simulate without -o writes <scene name>.csv in the current folder and says so",
          "[simulate][outputs]") {
    const std::string dir = scratch_dir("default");
    heavy_scene(dir);
    const run_result r = run_rotgen("simulate top.yaml", dir);
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("wrote   top.csv (11 samples, the default name") != std::string::npos);
    CHECK(without_provenance(read_file(dir + "/top.csv")).rfind("t,theta\n0,0.5\n", 0) == 0);
}

TEST_CASE("simulate -o - writes the CSV to standard output and the summary to standard error",
          "[simulate][outputs]") {
    const std::string dir = scratch_dir("stdout");
    const run_result r = run_rotgen("simulate '" + heavy_scene(dir) + "' -o -");
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(without_provenance(r.out).rfind("t,theta\n0,0.5\n", 0) == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 13); // provenance, header, 11 samples
    CHECK(r.err.find("rotgen simulate ") == 0);
    CHECK_FALSE(fs::exists(dir + "/-"));
}

TEST_CASE("simulate refuses an output that names one of its inputs and changes nothing",
          "[simulate][outputs]") {
    const std::string dir = scratch_dir("inputs");
    const std::string scene = heavy_scene(dir);
    const std::string before = read_file(scene);
    run_result r = run_rotgen("simulate '" + scene + "' -o '" + scene + "'");
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: " + scene + ": -o would write over the scene '" + scene +
                       "', a file this command reads\n");
    // the model, through another path to the same file (a symlink)
    fs::create_symlink(model_path("heavy_top"), dir + "/model_link.csv");
    r = run_rotgen("simulate '" + scene + "' -o '" + dir + "/model_link.csv'");
    CHECK(r.status == 2);
    CHECK(r.err.find("-o would write over the model '" + model_path("heavy_top") + "'") !=
          std::string::npos);
    CHECK(fs::is_symlink(dir + "/model_link.csv"));
    CHECK(read_file(scene) == before);
    CHECK(entries_in(dir) == 2); // the scene and the link
}

TEST_CASE("simulate writes through a symlink and into a named pipe, never replacing them",
          "[simulate][outputs]") {
    const std::string dir = scratch_dir("links");
    const std::string scene = heavy_scene(dir);
    fs::create_symlink("target.csv", dir + "/link.csv"); // dangling until written
    run_result r = run_rotgen("simulate '" + scene + "' -o '" + dir + "/link.csv'");
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(fs::is_symlink(dir + "/link.csv"));
    CHECK(without_provenance(read_file(dir + "/target.csv")).rfind("t,theta\n", 0) == 0);
    // a named pipe, read by cat: written through, not replaced by a regular file (a rename onto
    // it would leave cat waiting and a regular file in its place)
    REQUIRE(::mkfifo((dir + "/pipe.csv").c_str(), 0600) == 0);
    const std::string cmd = "cd '" + dir + "' && { timeout 120 cat pipe.csv > copy.txt & " +
                            "reader=$!; '" + std::string(ROTGEN_EXE) + "' simulate '" + scene +
                            "' -o pipe.csv -q; rc=$?; wait $reader; exit $rc; }";
    CHECK(std::system(cmd.c_str()) == 0);
    CHECK(fs::is_fifo(dir + "/pipe.csv"));
    CHECK(without_provenance(read_file(dir + "/copy.txt")).rfind("t,theta\n", 0) == 0);
}

TEST_CASE("simulate --plot writes PNG, SVG or PDF by the extension and refuses others",
          "[simulate][outputs]") {
    const std::string dir = scratch_dir("plots");
    const std::string scene = heavy_scene(dir);
    const std::vector<std::pair<std::string, std::string>> formats{
        {"png", "\x89PNG"}, {"svg", "<?xml"}, {"pdf", "%PDF"}};
    for (const auto& [ext, magic] : formats) {
        const run_result r =
            run_rotgen("simulate '" + scene + "' -o - --plot '" + dir + "/p." + ext + "'");
        INFO(ext << ": " << r.err);
        CHECK(r.status == 0);
        CHECK(read_file(dir + "/p." + ext).rfind(magic, 0) == 0);
    }
    const run_result r =
        run_rotgen("simulate '" + scene + "' -o '" + dir + "/x.csv' --plot '" + dir + "/p.jpg'");
    CHECK(r.status == 2);
    CHECK(r.err == "rotgen: error: " + dir +
                       "/p.jpg: cannot tell the plot format from the extension '.jpg' "
                       "(expected .png, .svg or .pdf)\n");
    CHECK_FALSE(fs::exists(dir + "/x.csv"));
    CHECK_FALSE(fs::exists(dir + "/p.jpg"));
}

TEST_CASE("max_steps reached is exit 3 with a partial file, not a chart switch",
          "[simulate][outputs]") {
    const std::string dir = scratch_dir("max_steps");
    const std::string scene =
        heavy_scene(dir, "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12, max_steps: 20}\n");
    const run_result r = run_rotgen("simulate '" + scene + "' -o '" + dir + "/out.csv'");
    INFO(r.out << r.err);
    CHECK(r.status == 3);
    CHECK(r.out.find("chart") == std::string::npos); // far from theta = 0: no switch
    CHECK(r.err.find("the run stopped at t = ") != std::string::npos);
    CHECK(r.err.find("max_steps") != std::string::npos);
    CHECK(r.err.find("are in " + dir + "/out.partial.csv") != std::string::npos);
    CHECK_FALSE(fs::exists(dir + "/out.csv"));
    const std::string partial = read_file(dir + "/out.partial.csv");
    const auto rows = std::count(partial.begin(), partial.end(), '\n') - 1;
    CHECK(rows >= 1); // observed: the samples before step 20 (t < 1)
    CHECK(rows < 11);
}

TEST_CASE("a conserved momentum that starts at 0 gets an absolute drift, not a relative one",
          "[simulate][outputs]") {
    const std::string dir = scratch_dir("drift");
    std::ofstream(dir + "/top.yaml")
        << "model: " << model_path("heavy_top") << "\n"
        << "initial: {theta: 0.5, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\ntime: "
           "{end: 1, samples: 11}\nrecord: [theta]\n";
    const run_result r = run_rotgen("simulate top.yaml", dir);
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    // p_phi = I1 phi_dot sin^2 theta + I3 cos theta (phi_dot cos theta + psi_dot) (5.74) = 0 at
    // rest
    CHECK(r.out.find("p_phi(0)| = 0 (absolute: p_phi(0) is near 0)") != std::string::npos);
    CHECK(r.out.find("energy(0)| = ") != std::string::npos);
    CHECK(r.out.find("(relative ") != std::string::npos); // the energy, M g h cos(0.5) != 0
}

TEST_CASE("a long run shows a progress line on a terminal only, erased at the end",
          "[simulate][outputs]") {
    const std::string dir = scratch_dir("progress");
    // 2e7 fixed RK4 steps: several seconds, well past the one second before the line appears
    std::ofstream(dir + "/long.yaml")
        << "model: " << model_path("heavy_top") << "\n"
        << "initial: {theta: 0.5, psi_dot: 30, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0}\ntime: "
           "{end: 2000, samples: 1001}\n"
        << "record: [theta]\nintegrator: {method: rk4, step: 1e-4, max_steps: 1e9}\n";
    // on a terminal (a pseudo-terminal from util-linux's script)
    const std::string cmd = "cd '" + dir + "' && script -qec \"'" + std::string(ROTGEN_EXE) +
                            "' simulate long.yaml -o a.csv\" /dev/null > tty.txt";
    REQUIRE(std::system(cmd.c_str()) == 0);
    const std::string tty = read_file(dir + "/tty.txt");
    CHECK(tty.find("rotgen: t = ") != std::string::npos);
    CHECK(tty.find("\r\033[K") != std::string::npos); // erased before the summary
    // not on a terminal, and not with --quiet: the same run, long enough for the line (its
    // summary says more than a second integrating)
    run_result r = run_rotgen("simulate long.yaml -o b.csv", dir);
    CHECK(r.status == 0);
    CHECK(r.err.empty());
    const auto at = r.out.find("time    ");
    REQUIRE(at != std::string::npos);
    // "time    3.08 s integrating" (the unit that fits: us, ms or s): more than a second
    std::istringstream time_line(r.out.substr(at + 8));
    double value = 0;
    std::string unit;
    time_line >> value >> unit;
    const double seconds = unit == "s" ? value : unit == "ms" ? value / 1e3 : value / 1e6;
    CHECK(seconds > 1); // observed 3.08 s on 2 loaded cores
    r = run_rotgen("simulate long.yaml -o c.csv --quiet", dir);
    CHECK(r.status == 0);
    CHECK(r.out.empty());
    CHECK(r.err.empty());
}

TEST_CASE("the samples are at t_start + k (t_end - t_start) / (samples - 1)",
          "[simulate][outputs]") {
    const std::string dir = scratch_dir("grid");
    std::ofstream(dir + "/top.yaml")
        << "model: " << model_path("heavy_top") << "\n"
        << "initial: {theta: 0.5, psi_dot: 30, phi: 0, psi: 0, phi_dot: 0, theta_dot: 0}\n"
        << "time: {start: 2, end: 3, samples: 11}\nrecord: [theta]\n";
    const run_result r = run_rotgen("simulate top.yaml -o - -q", dir);
    REQUIRE(r.status == 0);
    std::istringstream rows(without_provenance(r.out));
    std::string line;
    std::getline(rows, line); // the header
    std::vector<double> t;
    while (std::getline(rows, line))
        t.push_back(std::stod(line.substr(0, line.find(','))));
    REQUIRE(t.size() == 11);
    for (std::size_t k = 0; k < t.size(); ++k)
        CHECK(t[k] == Approx(2 + 0.1 * double(k)).margin(1e-15)); // as computed, to the last bit
}
