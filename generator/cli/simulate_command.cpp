// rotgen simulate SCENE.yaml [-o out.csv] [--events FILE] [--plot out.png] [--view FILE]
//                 [--plot-axis FILE] [--plot-polhode FILE] [--from RUN.csv]
// [--timings]
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "simulate/simulate.hpp"
#include "tune/tune.hpp"

#include <iostream>

namespace rotgen {

namespace {

const command_spec simulate_command{
    "simulate",
    "scene file",
    "SCENE.yaml [-o out.csv] [--events FILE] [--plot out.png] [--view run.html] [--plot-axis "
    "axis.png] [--plot-polhode polhode.png] [--from RUN.csv] [--timings] [--quiet]",
    "Integrates the scene: derives the model's equations, emits and compiles the scene's form\n"
    "(cached), integrates it and records the scene's quantities at its sample times. Prints a\n"
    "summary (steps, evaluations, invariant drifts) on standard output. A run that cannot finish\n"
    "exits 3 with its rows in <output>.partial.csv (its events in <output>.partial.events.csv).\n"
    "Outputs must be distinct files, none of them the scene or the model (exit 2 otherwise).\n"
    "They appear together once all are complete: exit 2 leaves no file (standard output and\n"
    "devices, written first, keep what they got before a later output failed).\n\n"
    "example: rotgen simulate models/scenes/heavy_top_nutation.yaml -o nutation.csv --plot "
    "nutation.png",
    {{"-o",
      "FILE",
      "the samples as CSV (header t,<recorded columns>); - for standard output;\n"
      "                     default <scene name>.csv. Every CSV starts with the line\n"
      "                     # rotgen VERSION model NAME sha256 HASH form FORM",
      {"--output"}},
     {"--events",
      "FILE",
      "the scene's events as CSV (header event,t,<recorded columns>);\n"
      "                     default <output stem>.events.csv when the scene has events\n"
      "                     (<scene name>.events.csv when -o is -, a device or a FIFO)",
      {}},
     {"--plot", "FILE", "the recorded quantities against t (gnuplot): .png, .svg or .pdf", {}},
     {"--view", "FILE", "a self-contained HTML page that plays the run in 3D in a browser", {}},
     {"--plot-axis",
      "FILE",
      "the figure axis's path on the unit sphere (loops, cusps, waves);\n"
      "                     its data in FILE with the extension .axis.csv",
      {}},
     {"--plot-polhode",
      "FILE",
      "the polhode: the body angular momentum's path on its sphere;\n"
      "                     its data in FILE with the extension .polhode.csv",
      {}},
     {"--from",
      "FILE",
      "start from the last row of an earlier run of the same model and form\n"
      "                     (its line 1 says which): its t and state (the scene's form's,\n"
      "                     recorded); the scene gives the rest",
      {}},
     {"--timings", "", "print the wall time of each pipeline stage to standard error", {}},
     {"--quiet", "", "no summary and no progress line (errors are still reported)", {"-q"}}}};

} // namespace

int cmd_simulate(const std::vector<std::string>& args) {
    const parsed_options o = parse_options(simulate_command, args);
    if (o.help) {
        std::cout << help_text(simulate_command);
        return 0;
    }
    simulate_request request;
    request.scene = o.operand;
    request.csv = o.value("-o");
    request.plot = o.value("--plot");
    request.events = o.value("--events");
    request.view = o.value("--view");
    request.plot_axis = o.value("--plot-axis");
    request.plot_polhode = o.value("--plot-polhode");
    request.from = o.value("--from");
    request.timings = o.has("--timings");
    request.quiet = o.has("--quiet");
    request.resolve = [](scene_spec& s) { resolve_auto(s); }; // method auto
    return simulate(request);
}

} // namespace rotgen
