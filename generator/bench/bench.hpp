// rotgen bench: the work-precision report of one scene (docs/architecture.md; the command line is
// cli/bench_command.cpp).
#pragma once

#include <string>

namespace rotgen {

struct bench_options {
    std::string scene;    // the scene file
    std::string dir;      // the output directory (cli default: bench-out/<scene name>)
    bool quick = false;   // fewer configurations
    long long_steps = 0;  // steps of the long-run drift check; 0: none
    bool timings = false; // one line per pipeline stage to stderr
};

// Runs the bench; returns the exit status. Throws user_error for bad input.
int run_bench(const bench_options& options);

// The plan such a run follows (plan.txt), without writing or compiling anything.
std::string bench_plan_text(const bench_options& options);

} // namespace rotgen
