#include "cli/cli.hpp"

#include "cli/commands.hpp"
#include "support/error.hpp"
#include "support/signals.hpp"
#include "support/standard_output.hpp"

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace rotgen {

namespace {

const char* const usage =
    "usage: rotgen <command> [options]   (rotgen <command> --help for each command's options)\n"
    "\n"
    "  inspect MODEL.yaml   the derived equations (text, LaTeX or JSON)\n"
    "  inspect SCENE.yaml   the same for the scene's model, then the scene's events\n"
    "  emit MODEL.yaml -o DIR\n"
    "                       a C++ header with the model's kernels (rhs, jacobian, energy, ...)\n"
    "  simulate SCENE.yaml  integrate a scene: CSV, plot, invariant drifts\n"
    "  bench SCENE.yaml     the work-precision report of a scene (rotgen against peers)\n"
    "  sweep SCENE.yaml -o DIR\n"
    "                       an ensemble of the scene (varied initial values and parameters)\n"
    "  view RUN.csv --scene SCENE.yaml\n"
    "                       a self-contained HTML page that plays the run in 3D in a browser\n"
    "  tune SCENE.yaml --error E [-o tuned.yaml]\n"
    "                       the fastest integrator reaching an error (method: auto), as a scene\n"
    "  fit SCENE.yaml --data measured.csv --free KEY,...\n"
    "                       fit initial values and parameters to measurements (least squares)\n"
    "\n"
    "  help [COMMAND]       this text, or a command's options (also rotgen COMMAND --help)\n"
    "  --version            the version\n"
    "\n"
    "exit status: 0 success; 2 input rejected, nothing written (one line on stderr names the file\n"
    "and the place); 3 a run started but could not finish (its rows in <output>.partial.csv);\n"
    "130/143 interrupted (SIGINT/SIGTERM), nothing left behind; 1 internal error\n";

// A diagnostic is one line whatever the input held: control characters (a newline in a quoted YAML
// key, a NUL) are shown escaped.
std::string one_line(const std::string& text) {
    std::string out;
    for (unsigned char c : text) {
        if (c == '\n')
            out += "\\n";
        else if (c == '\t')
            out += "\\t";
        else if (c < 0x20 || c == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02x", c);
            out += buf;
        } else
            out += static_cast<char>(c);
    }
    return out;
}

bool is_help_word(const std::string& word) {
    return word == "help" || word == "--help" || word == "-h";
}

// Runs the command `args` names; returns its exit status.
int run_command(std::vector<std::string> args) {
    if (!args.empty() && args[0] == "help") { // rotgen help [COMMAND] = rotgen COMMAND --help
        if (args.size() == 1 || is_help_word(args[1]))
            args = {"--help"};
        else
            args = {args[1], "--help"};
    }
    if (args.empty() || args[0] == "--help" || args[0] == "-h") {
        std::cout << usage;
        return args.empty() ? 2 : 0;
    }
    if (args[0] == "--version") {
        std::cout << "rotgen " << ROTGEN_VERSION << "\n";
        return 0;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    if (command == "inspect") return cmd_inspect(args);
    if (command == "emit") return cmd_emit(args);
    if (command == "simulate") return cmd_simulate(args);
    if (command == "bench") return cmd_bench(args);
    if (command == "sweep") return cmd_sweep(args);
    if (command == "view") return cmd_view(args);
    if (command == "tune") return cmd_tune(args);
    if (command == "fit") return cmd_fit(args);
    const std::string best = closest_name(
        command, {"inspect", "emit", "simulate", "bench", "sweep", "view", "tune", "fit", "help"});
    throw user_error({},
                     "unknown command '" + command + "'" +
                         (best.empty() ? "" : "; did you mean '" + best + "'?") +
                         " (expected inspect, emit, simulate, bench, sweep, view, tune or fit; see "
                         "rotgen --help)");
}

// bench and sweep write their folder as they go (sweep's journal is what --resume continues):
// a standard output that fails after such a command finished cannot take those files back, so
// the run is one that started and could not finish (status 3), its files kept and complete.
bool writes_as_it_goes(const std::string& command) {
    return command == "bench" || command == "sweep";
}

void report(const user_error& e) {
    pause_test_hook("report");
    std::cerr << "rotgen: error: " << one_line(e.message()) << "\n";
}

} // namespace

int run_cli(int argc, char** argv) {
    try {
        const std::vector<std::string> args(argv + 1, argv + argc);
        const int status = run_command(args);
        try {
            flush_standard_output(); // a full disk behind standard output is an error too
        } catch (const user_error& e) {
            if (status != 0) { // 3: the partial rows were written, and say so already
                report(e);
                return status;
            }
            if (!args.empty() && writes_as_it_goes(args[0])) {
                std::cerr << "rotgen: error: " << one_line(e.message()) << " after the " << args[0]
                          << " finished: the files it wrote in its folder are complete and kept\n";
                return 3;
            }
            report(e);
            return 2;
        }
        return status;
    } catch (const user_error& e) {
        report(e);
        return 2;
    } catch (const std::exception& e) {
        pause_test_hook("report");
        std::cerr << "rotgen: internal error: " << one_line(e.what()) << "\n";
        return 1;
    }
}

} // namespace rotgen
