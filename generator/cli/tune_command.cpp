// rotgen tune SCENE.yaml [--error E] [-o tuned.yaml] [--verbose]
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "scene/scene.hpp"
#include "support/atomic_file.hpp"
#include "support/format.hpp"
#include "tune/tune.hpp"
#include "tune/tuned_scene.hpp"

#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace rotgen {

namespace {

const command_spec tune_command{
    "tune",
    "scene file",
    "SCENE.yaml [--error E] [-o tuned.yaml] [--verbose]",
    "Chooses the integrator (method and tolerance, and the form when the scene gives no form:)\n"
    "that runs the scene fastest with an error at most E at its samples, as `method: auto`\n"
    "does: the bench's error measure (the largest over the samples of the attitude error and\n"
    "|omega - omega_ref| / |omega_ref|) against a tight reference, on the scene's whole span.\n"
    "Prints the choice as scene lines; with -o, writes the scene with them. The choice is cached\n"
    "by the content of scene and model; another machine may choose otherwise. Exit 2 when no\n"
    "configuration reaches E (the message names the smallest error reached).\n\n"
    "example: rotgen tune models/scenes/heavy_top_nutation.yaml --error 1e-8 -o tuned.yaml",
    {{"--error", "E", "the largest error accepted (default: the scene's integrator error)", {}},
     {"-o", "FILE", "the scene with the chosen form and integrator (YAML)", {"--output"}},
     {"--verbose", "", "one line per configuration measured", {"-v"}}}};

double error_of(const parsed_options& o) {
    const std::string& v = o.value("--error");
    char* end = nullptr;
    const double e = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0' || !(e > 0 && e < 1))
        usage_error(tune_command, "--error must be a number between 0 and 1, not '" + v + "'");
    return e;
}

} // namespace

int cmd_tune(const std::vector<std::string>& args) {
    const parsed_options o = parse_options(tune_command, args);
    if (o.help) {
        std::cout << help_text(tune_command);
        return 0;
    }
    scene_spec scene = load_scene(o.operand, "tune");
    if (o.has("--error")) {
        scene.integrator = integrator_spec{};
        scene.integrator.method = "auto";
        scene.integrator.error = error_of(o);
    } else if (scene.integrator.method != "auto")
        usage_error(tune_command, "tune needs --error E (or a scene with method: auto)");
    const std::string out = o.value("-o");
    std::optional<atomic_file> file;
    if (!out.empty()) file.emplace(out, std::vector<std::string>{o.operand, scene.model.file});
    const bool form_given = scene.form_given;
    const auto_choice c = resolve_auto(scene, o.has("--verbose") ? &std::cerr : nullptr);
    std::cout << "rotgen tune " << o.operand << "\n"
              << "  method  auto: " << scene.integrator.auto_choice << "\n"
              << "  target  error " << short_number(scene.integrator.error)
              << " (the largest over the samples of the attitude error and |dw|/|w|)\n"
              << "  error   " << short_number(c.error) << " measured, in "
              << format_duration(c.run_seconds) << " integrating (reference floor "
              << short_number(c.floor) << ")\n"
              << "  scene   " << (form_given ? "" : "form: " + std::string(to_string(scene.form)))
              << (form_given ? "" : "\n          ") << integrator_line(scene.integrator) << "\n";
    if (file) {
        const std::string dir = std::filesystem::path(out).parent_path().string();
        file->stream() << tuned_scene_text(scene, dir.empty() ? "." : dir, !form_given);
        file->commit();
        std::cout << "  wrote   " << out << "\n";
    }
    return 0;
}

} // namespace rotgen
