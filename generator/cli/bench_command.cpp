// rotgen bench SCENE.yaml [-o DIR] [--quick] [--long-steps N] [--timings]
#include "bench/bench.hpp"
#include "cli/commands.hpp"
#include "cli/options.hpp"

#include <cstdlib>
#include <iostream>

namespace rotgen {

namespace {

const command_spec bench_command{
    "bench",
    "scene file",
    "SCENE.yaml [-o DIR] [--quick] [--long-steps N] [--timings]",
    "The work-precision report of the scene: every integrator, tolerance, scalar type and\n"
    "formulation of rotgen, and the peers Boost.Odeint and SUNDIALS CVODE driving the same\n"
    "kernels, against an exact or a much tighter reference. Writes results.csv, results.md,\n"
    "final_states.csv, drift.csv and plots in DIR.\n\n"
    "example: rotgen bench models/scenes/free_top_workprecision.yaml --quick -o bench-out/free_top",
    {{"-o", "DIR", "the output directory (default bench-out/<scene name>)", {"--output"}},
     {"--quick", "", "fewer configurations (a minute instead of several)", {}},
     {"--long-steps",
      "N",
      "steps of the long-run drift check, 0 to 1e8 (default 1e6; 1e4 with --quick)",
      {}},
     {"--timings", "", "print the wall time of each pipeline stage to standard error", {}}}};

long long_steps_of(const parsed_options& o) {
    if (!o.has("--long-steps")) return o.has("--quick") ? 10000 : 1000000;
    const std::string& v = o.value("--long-steps");
    char* end = nullptr;
    const long n = std::strtol(v.c_str(), &end, 10);
    if (v.empty() || *end || n < 0 || n > 100000000)
        usage_error(bench_command,
                    "--long-steps needs a whole number of steps in [0, 1e8], got '" + v + "'");
    return n;
}

std::string stem_of(const std::string& path) {
    std::string stem = path.substr(path.find_last_of('/') + 1);
    if (const auto dot = stem.rfind('.'); dot != std::string::npos && dot > 0) stem.erase(dot);
    return stem;
}

} // namespace

int cmd_bench(const std::vector<std::string>& args) {
    const parsed_options o = parse_options(bench_command, args);
    if (o.help) {
        std::cout << help_text(bench_command);
        return 0;
    }
    bench_options b;
    b.scene = o.operand;
    b.dir = o.value("-o", "bench-out/" + stem_of(o.operand));
    b.quick = o.has("--quick");
    b.long_steps = long_steps_of(o);
    b.timings = o.has("--timings");
    return run_bench(b);
}

} // namespace rotgen
