// rotgen inspect MODEL.yaml [--format text|latex|json] [--inertia [--symbolic]]
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "derive/derive.hpp"
#include "inspect/inspect.hpp"
#include "spec/spec.hpp"

#include <iostream>

namespace rotgen {

namespace {

const command_spec inspect_command{
    "inspect",
    "model file",
    "MODEL.yaml [--format text|latex|json] [--inertia [--symbolic]]",
    "Prints the derived equations of the model: kinetic and potential energy, Lagrangian, "
    "momenta,\n"
    "mass matrix, Euler-Lagrange equations, Hamiltonian and Hamilton's equations, cyclic\n"
    "coordinates and the energy, as text, LaTeX or JSON (expressions SymPy can parse).",
    {{"--format", "text|latex|json", "the output format (default text)", {}},
     {"--inertia",
      "",
      "also the inertia tensor, principal moments and axes, class and stability",
      {}},
     {"--symbolic",
      "",
      "with --inertia: stability rates as expressions too (default: their values)",
      {}}}};

output_format format_of(const std::string& f) {
    if (f.empty() || f == "text") return output_format::text;
    if (f == "latex") return output_format::latex;
    if (f == "json") return output_format::json;
    usage_error(inspect_command, "unknown format '" + f + "' (expected text, latex or json)");
}

} // namespace

int cmd_inspect(const std::vector<std::string>& args) {
    const parsed_options o = parse_options(inspect_command, args);
    if (o.help) {
        std::cout << help_text(inspect_command);
        return 0;
    }
    const output_format format = format_of(o.value("--format"));
    if (o.has("--symbolic") && !o.has("--inertia"))
        usage_error(inspect_command, "--symbolic needs --inertia");
    const model_spec spec = load_model(o.operand);
    // text and LaTeX --inertia show the inertia report alone, which needs no derivation (and a
    // linear rotor has none)
    if (o.has("--inertia") && format != output_format::json) {
        std::cout << inspect_inertia(spec, format, o.has("--symbolic"));
        return 0;
    }
    const derivation d = derive(spec);
    std::cout << inspect(spec, d, format, o.has("--inertia"), o.has("--symbolic"));
    return 0;
}

} // namespace rotgen
