// Messages that say what is wrong (issue 24): each bad input below gets one located line that
// names the problem, exit status 2 and nothing written; and the summaries say what ran, in units
// that fit, on the stream the one rule gives (standard output unless it carries data).
#include "error_sites.hpp"
#include "support.hpp"
#include "support/format.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <regex>
#include <tuple>

using namespace rotgen::test;
namespace fs = std::filesystem;

namespace {

const std::string start = "initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, "
                          "psi_dot: 30}\ntime: {end: 1, samples: 11}\n";

// A scene of the heavy top in the build tree (removed at scope exit), `extra` lines after `start`.
struct top_scene {
    scratch_file file;
    top_scene(const std::string& name, const std::string& extra)
        : file(name, "model: " + model_path("heavy_top") + "\n" + start + extra) {}
};

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

} // namespace

TEST_CASE("messages: a model file where a scene is expected says so", "[cli][messages]") {
    const scratch_file model("messages_model.yaml", "name: top\nparameters: {I1: 1}\n"
                                                    "inertia: [I1, I1, 0.5]\n");
    const scratch_dir out("messages_model_out");
    for (const std::string command : {"simulate", "sweep", "bench"}) {
        INFO(command);
        check_error_line(run_rotgen(command + " messages_model.yaml -o '" + out.path.string() + "'",
                                    ROTGEN_BINARY_DIR),
                         "messages_model.yaml:3:1: this is a model file (it has 'inertia:'); " +
                             command + " takes a scene, which names its model with 'model:'");
        CHECK(!fs::exists(out.path));
    }
    const scratch_file parts("messages_parts.yaml",
                             "name: ball\nbody:\n  parts:\n    - sphere: {mass: 1, radius: 1, at: "
                             "[0, 0, 0]}\n");
    check_error_line(run_rotgen("simulate messages_parts.yaml", ROTGEN_BINARY_DIR),
                     "messages_parts.yaml:2:1: this is a model file (it has 'body:'); simulate "
                     "takes a scene, which names its model with 'model:'");
}

TEST_CASE("messages: a scene given to emit says so and names its model", "[cli][messages]") {
    const scratch_file scene("messages_scene.yaml", "model: ../heavy_top.yaml\n" + start);
    const scratch_dir out("messages_scene_out");
    check_error_line(
        run_rotgen("emit messages_scene.yaml -o '" + out.path.string() + "'", ROTGEN_BINARY_DIR),
        "messages_scene.yaml:1:8: this is a scene file (it names its model with 'model:'); emit "
        "takes a model file, such as the one it names, '../heavy_top.yaml'");
    CHECK(!fs::exists(out.path));
}

TEST_CASE("messages: an empty record list asks for a quantity", "[cli][messages]") {
    const top_scene s("messages_record.yaml", "record: []\n");
    check_error_line(run_rotgen("simulate messages_record.yaml", ROTGEN_BINARY_DIR),
                     "messages_record.yaml:4:9: 'record' must list at least one quantity");
    CHECK(!fs::exists(std::string(ROTGEN_BINARY_DIR) + "/messages_record.csv"));
}

TEST_CASE("messages: a folder where a file is expected is named as such", "[cli][messages]") {
    const scratch_dir folder("messages_folder.yaml");
    fs::create_directory(folder.path);
    for (const std::string command : {"inspect", "simulate", "emit"}) {
        INFO(command);
        check_error_line(run_rotgen(command + " messages_folder.yaml" +
                                        (command == "emit" ? " -o messages_folder_out" : ""),
                                    ROTGEN_BINARY_DIR),
                         "messages_folder.yaml: is a folder, not a file; give a model or scene "
                         "file");
    }
    // a scene whose model: names a folder
    const scratch_file via("messages_via.yaml", "model: messages_folder.yaml\n" + start);
    check_error_line(run_rotgen("simulate messages_via.yaml", ROTGEN_BINARY_DIR),
                     "messages_folder.yaml: is a folder, not a file; give a model or scene file");
}

TEST_CASE("messages: a binary file and tab indentation are named as such", "[cli][messages]") {
    using row = std::tuple<std::string, std::string, std::string>;
    const auto [name, text, line] = GENERATE(table<std::string, std::string, std::string>({
        row{"an ELF header",
            std::string("\x7f"
                        "ELF\x02\x01\x01\0\0\0",
                        10),
            ":1:1: not a text file (byte 0x7f here): a model or scene is YAML text"},
        row{"a NUL after text", std::string("name: top\ninertia: [1, 1, 1]\0\n", 30),
            ":2:19: not a text file (byte 0x00 here): a model or scene is YAML text"},
        row{"a tab before a key", "name: top\nparameters:\n\tI1: 1\ninertia: [I1, I1, 1]\n",
            ":3:1: a tab in the indentation: YAML forbids tabs there; indent with spaces"},
        row{"a tab after spaces",
            "name: top\nparameters:\n  I1: 1\n  \tI3: 1\ninertia: [1, 1, 1]\n",
            ":4:3: a tab in the indentation: YAML forbids tabs there; indent with spaces"},
    }));
    INFO(name);
    const scratch_file file("messages_text.yaml", text);
    check_error_line(run_rotgen("inspect messages_text.yaml", ROTGEN_BINARY_DIR),
                     "messages_text.yaml" + line);
}

TEST_CASE("messages: UTF-8 text and a tab inside a line are still read", "[cli][messages]") {
    const scratch_file file("messages_utf8.yaml",
                            "name: top\ndescription: \"Kreisel, \xc3\xa9t\xc3\xa9 \xe2\x80\x94 "
                            "\xf0\x9f\x8c\x80\"\ninertia: [1,\t1, 0.5]\t# tabs between tokens\n");
    const run_result r = run_rotgen("inspect messages_utf8.yaml", ROTGEN_BINARY_DIR);
    INFO(r.err);
    CHECK(r.status == 0);
    CHECK(contains(r.out, "model top (messages_utf8.yaml)"));
}

TEST_CASE("messages: a potential singular at the start is not told to shrink the rates",
          "[cli][messages]") {
    const scratch_file scene("messages_singular.yaml",
                             "model: {name: pole, inertia: [1, 1, 0.5], potential: 1/(theta - "
                             "0.5)}\n" +
                                 start);
    const run_result r = run_rotgen("simulate messages_singular.yaml", ROTGEN_BINARY_DIR);
    check_error_line(r, "messages_singular.yaml:2:10: the model's equations are not finite at the "
                        "initial state (theta_ddot = inf in f(t0, y0) at t = 0.0): its "
                        "potential, torque or damping is singular there; start the scene away "
                        "from that state");
    CHECK(!contains(r.err, "smaller initial rates"));
    // rates too large for double precision still get the advice about the rates
    const scratch_file fast("messages_fast.yaml",
                            "model: " + model_path("heavy_top") +
                                "\ninitial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: "
                                "0, psi_dot: 1e200}\ntime: {end: 1}\n");
    const run_result f = run_rotgen("simulate messages_fast.yaml", ROTGEN_BINARY_DIR);
    CHECK(f.status == 2);
    CHECK(contains(f.err, "; give smaller initial rates or momenta"));
}

TEST_CASE("messages: did you mean, for commands, options and case", "[cli][messages]") {
    check_error_line(run_rotgen("simulat x.yaml"),
                     "unknown command 'simulat'; did you mean 'simulate'? (expected inspect, "
                     "emit, simulate, bench, sweep, view, tune or fit; see rotgen --help)");
    const run_result r = run_rotgen("swep");
    CHECK(r.err.rfind("rotgen: error: unknown command 'swep'; did you mean 'sweep'?", 0) == 0);
    CHECK(!contains(r.err, "rotgen: error: rotgen:")); // no doubled prefix
    check_error_line(run_rotgen("simulate '" + model_path("heavy_top") + "' --outptu a.csv"),
                     "rotgen simulate: unknown option '--outptu' for simulate; did you mean "
                     "'--output'?");
    check_error_line(run_rotgen("sweep x.yaml --trajectries"),
                     "rotgen sweep: unknown option '--trajectries' for sweep; did you mean "
                     "'--trajectories'?");
    const top_scene s("messages_case.yaml", "integrator: {method: DOP853}\n");
    check_error_line(run_rotgen("simulate messages_case.yaml", ROTGEN_BINARY_DIR),
                     "messages_case.yaml:4:22: unknown integrator 'DOP853' (expected rk4, "
                     "dopri5, dop853, implicit_midpoint, rosenbrock, split2, split4, split6, "
                     "taylor or auto); did you mean 'dop853'?");
}

TEST_CASE("messages: the summary's model line names the form that ran", "[cli][messages]") {
    using row = std::tuple<std::string, std::string, std::string>;
    const auto [name, extra, line] = GENERATE(table<std::string, std::string, std::string>({
        row{"the scene's own form", "", ", lagrangian form, 6 states\n"},
        row{"a split method runs the body form", "integrator: {method: split2, step: 0.01}\n",
            ", body form, 7 states\n"},
    }));
    INFO(name);
    const top_scene s("messages_form.yaml", extra);
    const run_result r =
        run_rotgen("simulate messages_form.yaml -o messages_form.csv", ROTGEN_BINARY_DIR);
    INFO(r.out << r.err);
    CHECK(r.status == 0);
    CHECK(contains(r.out, "  model   heavy_top (" + model_path("heavy_top") + ")" + line));
    fs::remove(std::string(ROTGEN_BINARY_DIR) + "/messages_form.csv");
}

TEST_CASE("messages: a start at the gimbal lock names the body form in the summary",
          "[cli][messages]") {
    const scratch_file scene("messages_lock.yaml",
                             "model: " + model_path("heavy_top") +
                                 "\ninitial: {phi: 0, theta: 0, psi: 0, phi_dot: 0, theta_dot: "
                                 "0.5, psi_dot: 30}\ntime: {end: 0.1, samples: 11}\n"
                                 "record: [theta, energy]\n");
    const run_result r =
        run_rotgen("simulate messages_lock.yaml -o messages_lock.csv", ROTGEN_BINARY_DIR);
    INFO(r.out << r.err);
    CHECK(r.status == 0);
    CHECK(contains(r.out, ", body form, 7 states\n  chart   started in the body form"));
    fs::remove(std::string(ROTGEN_BINARY_DIR) + "/messages_lock.csv");
}

TEST_CASE("messages: durations in one unit that fits", "[cli][messages]") {
    using row = std::tuple<double, std::string>;
    const auto [seconds, text] = GENERATE(table<double, std::string>({
        row{1300.0, "1300 s"},
        row{12.34, "12.3 s"},
        row{1.3, "1.30 s"},
        row{0.99996, "1.00 s"}, // rounds up to the next unit
        row{0.0148, "14.8 ms"},
        row{0.000507, "507 us"},
        row{0.00099996, "1.00 ms"},
        row{2.5e-7, "0.250 us"},
        row{0.0, "0.000 us"},
    }));
    CHECK(rotgen::format_duration(seconds) == text);
}

TEST_CASE("messages: the summary's time line keeps its format", "[cli][messages]") {
    // every duration is <number> <s|ms|us>, never an exponent
    const run_result r = run_rotgen("simulate '" + std::string(ROTGEN_SOURCE_DIR) +
                                        "/models/scenes/falling_top.yaml' -o - --events "
                                        "messages_falling.events.csv",
                                    ROTGEN_BINARY_DIR);
    INFO(r.err);
    CHECK(r.status == 0);
    const std::regex time_line("  time    [0-9]+\\.?[0-9]* (s|ms|us) integrating; [0-9]+\\.?[0-9]* "
                               "(s|ms|us) deriving, [0-9]+\\.?[0-9]* (s|ms|us) emitting and "
                               "(loading the cached|compiling the) kernels\n");
    CHECK(std::regex_search(r.err, time_line));
    CHECK(!contains(r.err, "e+"));
    fs::remove(std::string(ROTGEN_BINARY_DIR) + "/messages_falling.events.csv");
}

TEST_CASE("messages: every summary goes to standard output unless it carries data",
          "[cli][messages]") {
    const scratch_dir out("messages_sweep_out");
    const run_result s = run_rotgen(
        "sweep '" + std::string(ROTGEN_SOURCE_DIR) +
        "/models/scenes/heavy_top_nutation.yaml' -j 1 --vary initial.theta=0.4:0.5:2 -o '" +
        out.path.string() + "'");
    INFO(s.err);
    CHECK(s.status == 0);
    CHECK(s.err.empty());
    CHECK(s.out.rfind("rotgen sweep ", 0) == 0);
    CHECK(contains(s.out, "  members 2 (grid over initial.theta), 2 ok, 0 failed"));
    CHECK(std::regex_search(s.out, std::regex("  time    [0-9.]+ (s|ms|us) running the members")));
    // simulate -o -: the CSV on standard output, the summary on standard error
    const run_result r = run_rotgen("simulate '" + std::string(ROTGEN_SOURCE_DIR) +
                                    "/models/scenes/heavy_top_nutation.yaml' -o -");
    CHECK(r.status == 0);
    CHECK(without_provenance(r.out).rfind("t,theta,", 0) == 0);
    CHECK(r.err.rfind("rotgen simulate ", 0) == 0);
}
