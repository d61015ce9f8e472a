// rotgen inspect MODEL.yaml|SCENE.yaml [--format text|latex|json] [--inertia [--symbolic]]
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "derive/derive.hpp"
#include "inspect/inspect.hpp"
#include "scene/scene.hpp"
#include "spec/spec.hpp"

#include <iostream>

namespace rotgen {

namespace {

const command_spec inspect_command{
    "inspect",
    "model or scene file",
    "MODEL.yaml|SCENE.yaml [--format text|latex|json] [--inertia [--symbolic]]",
    "Prints the derived equations of the model: kinetic and potential energy, Lagrangian, "
    "momenta,\n"
    "mass matrix, Euler-Lagrange equations, Hamiltonian and Hamilton's equations, cyclic\n"
    "coordinates and the energy, as text, LaTeX or JSON (expressions SymPy can parse).\n"
    "Given a scene file, those of its model, then the scene's event functions.",
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

// The model's report: text and LaTeX --inertia show the inertia report alone, which needs no
// derivation (and a linear rotor has none).
std::string model_text(const model_spec& spec, output_format format, bool inertia, bool symbolic) {
    if (inertia && format != output_format::json) return inspect_inertia(spec, format, symbolic);
    if (spec.rotor) return inspect_rotor(spec, format, inertia, symbolic);
    return inspect(spec, derive(spec), format, inertia, symbolic);
}

// The report followed by the scene's event functions (in JSON: one more member of the object).
std::string with_events(std::string text, const scene_spec& scene, output_format format) {
    if (scene.events.empty()) return text;
    const std::string events = describe_events(scene.events, scene.model.angles, format);
    if (format != output_format::json) return text + events;
    const auto close = text.rfind('}');
    const auto last = text.find_last_not_of(" \n", close - 1);
    return text.substr(0, last + 1) + ",\n  " + events + "\n" + text.substr(close);
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
    const bool inertia = o.has("--inertia"), symbolic = o.has("--symbolic");
    const YAML::Node root = load_yaml_file(o.operand);
    if (!(root.IsMap() && root["model"])) { // a model file
        std::cout << model_text(load_model(o.operand), format, inertia, symbolic);
        return 0;
    }
    const scene_spec scene = load_scene(o.operand); // a scene names its model
    std::cout << with_events(model_text(scene.model, format, inertia, symbolic), scene, format);
    return 0;
}

} // namespace rotgen
