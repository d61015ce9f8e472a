// rotgen view RUN.csv (--scene SCENE.yaml | --model MODEL.yaml) [-o run.html]
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "run/provenance.hpp"
#include "support/error.hpp"
#include "support/standard_output.hpp"
#include "view/view.hpp"

#include <iostream>
#include <optional>

namespace rotgen {

namespace {

const command_spec view_command{
    "view",
    "CSV file",
    "RUN.csv (--scene SCENE.yaml | --model MODEL.yaml) [-o run.html]",
    "Writes a self-contained HTML page that plays the run in 3D in a browser: the body (a solid\n"
    "shaped by its inertia), its axes, L, gravity and the trace of the figure axis on the unit\n"
    "sphere, with play/pause, speed, a time slider and orbit/zoom. The page needs no network.\n"
    "The CSV must hold the attitude: q0..q3, or the Euler angles phi, theta, psi.\n\n"
    "(rotgen simulate SCENE.yaml --view run.html writes the page of a run directly.)\n\n"
    "example: rotgen view run.csv --scene models/scenes/free_top_axis2.yaml",
    {{"-o", "FILE", "the page; default <CSV stem>.html", {"--output"}},
     {"--scene", "FILE", "the scene that wrote the CSV (its model and parameters)", {}},
     {"--model", "FILE", "the model, at its default parameters (instead of --scene)", {}}}};

std::string default_page(const std::string& csv) {
    std::string stem = csv;
    if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".csv") == 0)
        stem.erase(stem.size() - 4);
    return stem + ".html";
}

scene_spec scene_of(const parsed_options& o) {
    if (o.has("--scene") == o.has("--model"))
        usage_error(view_command,
                    "give the run's scene (--scene FILE) or its model (--model FILE)");
    if (o.has("--scene")) return load_scene(o.value("--scene"));
    scene_spec scene;
    scene.model = load_model(o.value("--model"));
    for (const auto& p : scene.model.parameters)
        scene.parameters.push_back(p.value);
    scene.file = scene.model.file;
    return scene;
}

// Refuses a run whose provenance line (run/provenance.hpp) names another model than the one given:
// the page would draw another body. A CSV without the line is drawn as it is.
void check_model(const csv_table& table, const std::string& csv, const scene_spec& scene,
                 const std::string& option) {
    const std::optional<csv_provenance> run = parse_provenance(table.provenance);
    const csv_provenance here = provenance_of(scene.model, scene.form);
    if (!run || (run->model == here.model && run->sha256 == here.sha256)) return;
    throw user_error({csv, 1, 1}, "the run is of model '" + run->model + "' (sha256 " +
                                      run->sha256.substr(0, 12) + "), not of the model '" +
                                      here.model + "' (sha256 " + here.sha256.substr(0, 12) +
                                      ") that " + option +
                                      " gives: the page would draw another "
                                      "body");
}

} // namespace

int cmd_view(const std::vector<std::string>& args) {
    const parsed_options o = parse_options(view_command, args);
    if (o.help) {
        std::cout << help_text(view_command);
        return 0;
    }
    const scene_spec scene = scene_of(o);
    const csv_table table = read_run_csv(o.operand);
    check_model(table, o.operand, scene, o.has("--scene") ? "--scene" : "--model");
    view_data data =
        view_of_rows(scene, table.columns, table.rows, {o.operand, table.header_line, 1});
    data.title = scene.model.name + " (" + o.operand + ")";
    data.source = o.operand + " and " + scene.file;
    const std::string page = o.value("-o", default_page(o.operand));
    output_set outputs;
    write_view(page, data, {o.operand, scene.file, scene.model.file}, &outputs);
    outputs.commit_streams();
    std::cout << "wrote " << page << " (" << table.rows.size() << " samples)\n";
    flush_standard_output(); // that line, checked before the page appears
    outputs.commit_files();
    return 0;
}

} // namespace rotgen
