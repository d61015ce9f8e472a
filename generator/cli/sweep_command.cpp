// rotgen sweep SCENE.yaml -o DIR [--vary KEY=FROM:TO:COUNT]... [-j N] [--lanes W] [--trajectories]
// [--resume] [--timings] [--quiet]
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "sweep/sweep.hpp"
#include "tune/tune.hpp"

#include <cstdlib>
#include <iostream>

namespace rotgen {

namespace {

const command_spec sweep_command{
    "sweep",
    "scene file",
    "SCENE.yaml -o DIR [--vary KEY=FROM:TO:COUNT]... [-j N] [--lanes W] [--trajectories] "
    "[--resume] [--timings] [--quiet]",
    "Runs an ensemble of the scene: the members vary its initial values and parameters as its\n"
    "sweep: block and the --vary options say (grid, zip or random). The model is derived and its\n"
    "kernels compiled once for all members. Writes DIR/summary.csv, one row per member in member\n"
    "order (the varied values, the final recorded values, the first time of each event,\n"
    "invariant drifts, steps, RHS evaluations, status), the same byte for byte on every run. A\n"
    "member that fails does not stop the others; the exit status is then 3. The files are\n"
    "written as the members finish, under partial names (a journal) until the sweep completes;\n"
    "an interrupted sweep keeps the journal of the members that finished, and the same\n"
    "command with --resume finishes it.\n\n"
    "example: rotgen sweep models/scenes/heavy_top_nutation.yaml -o tilt --vary "
    "initial.theta=0.1:1.5:64",
    {{"-o", "DIR", "the output directory (created if missing)", {"--output"}},
     {"--vary",
      "KEY=FROM:TO:COUNT",
      "vary initial.<name> or parameters.<name> over COUNT values from FROM to TO\n"
      "(or KEY=V1,V2,...; random mode: KEY=FROM:TO); repeatable, and\n"
      "replaces the scene's entry for the same key",
      {},
      false,
      true},
     {"-j", "N", "run N members at a time, on N threads (default: every core)", {"--jobs"}},
     {"--lanes",
      "W",
      "advance W neighbouring members together in SIMD lanes (rk4, dop853 or\n"
      "taylor; default 1: one at a time); a member a batch cannot carry (a chart\n"
      "switch, a failure) runs alone as without --lanes",
      {}},
     {"--trajectories",
      "",
      "also write DIR/trajectories.h5: every member's samples, [member, sample, column]",
      {}},
     {"--resume",
      "",
      "finish the interrupted sweep whose journal DIR holds (DIR/*.partial*),\n"
      "without running its finished members again; with no journal, run them all",
      {}},
     {"--timings", "", "print the wall time of each pipeline stage to standard error", {}},
     {"--quiet", "", "no summary and no progress line (errors are still reported)", {"-q"}}}};

// The value of `option`: a whole number from 1 to `most` (a usage error otherwise).
unsigned whole_number(const parsed_options& o, const std::string& option, const std::string& what,
                      long most) {
    const std::string& v = o.value(option);
    char* end = nullptr;
    const long n = std::strtol(v.c_str(), &end, 10);
    if (v.empty() || *end != '\0' || n < 1 || n > most)
        usage_error(sweep_command, option + " needs a whole number of " + what + " from 1 to " +
                                       std::to_string(most) + ", got '" + v + "'");
    return static_cast<unsigned>(n);
}

} // namespace

int cmd_sweep(const std::vector<std::string>& args) {
    const parsed_options o = parse_options(sweep_command, args);
    if (o.help) {
        std::cout << help_text(sweep_command);
        return 0;
    }
    if (!o.has("-o")) usage_error(sweep_command, "sweep needs an output directory: -o DIR");
    sweep_request q;
    q.scene = o.operand;
    q.directory = o.value("-o");
    q.vary = o.values("--vary");
    if (o.has("-j")) q.jobs = whole_number(o, "-j", "threads", 4096);
    if (o.has("--lanes")) q.lanes = whole_number(o, "--lanes", "lanes", 64);
    q.trajectories = o.has("--trajectories");
    q.timings = o.has("--timings");
    q.quiet = o.has("--quiet");
    q.resume = o.has("--resume");
    // method auto: tuned once for all, steps under error control, a method the lanes run
    const auto_use use = q.lanes > 1 ? auto_use::lanes : auto_use::ensemble;
    q.resolve = [use](scene_spec& s) { resolve_auto(s, nullptr, use); };
    return sweep(q);
}

} // namespace rotgen
