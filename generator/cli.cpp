#include "cli.hpp"

#include "commands.hpp"
#include "error.hpp"

#include <iostream>
#include <string>
#include <vector>

namespace rotgen {

namespace {

const char* const usage =
    "usage: rotgen inspect MODEL.yaml [--format text|latex|json]\n"
    "       rotgen emit MODEL.yaml -o DIR [--form lagrangian|hamiltonian|reduced|body]\n"
    "                  [--outputs rhs,jacobian,...] [--specialise]\n"
    "       rotgen simulate SCENE.yaml [-o out.csv] [--plot out.png]\n";

} // namespace

int run_cli(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    try {
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
        throw user_error({"rotgen"}, "unknown command '" + command + "' (expected inspect, emit or simulate; see rotgen --help)");
    } catch (const user_error& e) {
        std::cerr << "rotgen: error: " << e.message() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "rotgen: internal error: " << e.what() << "\n";
        return 1;
    }
}

} // namespace rotgen
