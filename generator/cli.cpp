#include "cli.hpp"

#include "derive.hpp"
#include "error.hpp"
#include "inspect.hpp"
#include "spec.hpp"

#include <iostream>
#include <string>
#include <vector>

namespace rotgen {

namespace {

const char* const usage =
    "usage: rotgen inspect MODEL.yaml [--format text|latex|json]\n";

user_error usage_error(const std::string& problem) { return user_error({"rotgen"}, problem); }

int cmd_inspect(const std::vector<std::string>& args) {
    std::string model;
    output_format format = output_format::text;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--format") {
            if (i + 1 >= args.size()) throw usage_error("--format needs a value (text|latex|json)");
            const std::string f = args[++i];
            if (f == "text") format = output_format::text;
            else if (f == "latex") format = output_format::latex;
            else if (f == "json") format = output_format::json;
            else throw usage_error("unknown format '" + f + "' (expected text, latex or json)");
        } else if (!a.empty() && a[0] == '-') {
            throw usage_error("unknown option '" + a + "' for inspect");
        } else if (model.empty()) {
            model = a;
        } else {
            throw usage_error("inspect takes one model file, got '" + model + "' and '" + a + "'");
        }
    }
    if (model.empty()) throw usage_error("inspect needs a model file");
    const model_spec spec = load_model(model);
    const derivation d = derive(spec);
    std::cout << inspect(spec, d, format);
    return 0;
}

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
        throw usage_error("unknown command '" + command + "'\n" + usage);
    } catch (const user_error& e) {
        std::cerr << "rotgen: error: " << e.message() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "rotgen: internal error: " << e.what() << "\n";
        return 1;
    }
}

} // namespace rotgen
