#include "cli/commands.hpp"
#include "derive/derive.hpp"
#include "support/error.hpp"
#include "inspect/inspect.hpp"
#include "spec/spec.hpp"

#include <iostream>

namespace rotgen {

namespace {
user_error usage_error(const std::string& problem) { return user_error({"rotgen inspect"}, problem); }
} // namespace

int cmd_inspect(const std::vector<std::string>& args) {
    std::string model;
    output_format format = output_format::text;
    bool with_inertia = false;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--format") {
            if (i + 1 >= args.size()) throw usage_error("--format needs a value (text|latex|json)");
            const std::string f = args[++i];
            if (f == "text") format = output_format::text;
            else if (f == "latex") format = output_format::latex;
            else if (f == "json") format = output_format::json;
            else throw usage_error("unknown format '" + f + "' (expected text, latex or json)");
        } else if (a == "--inertia") {
            with_inertia = true;
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
    std::cout << inspect(spec, d, format, with_inertia);
    return 0;
}

} // namespace rotgen
