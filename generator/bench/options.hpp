// rotgen bench: its command line, `rotgen bench SCENE.yaml [-o DIR] [--quick] [--long-steps N]`.
#pragma once

#include <string>
#include <vector>

namespace rotgen::bench {

extern const char* const bench_usage;

struct bench_options {
    std::string scene, dir;
    bool quick = false;
    long long_steps = -1; // -1: 10^6 (10^4 with --quick); 0: no long run
};

// The options of `rotgen bench ARGS...`, with the defaults filled in (DIR: bench-out/<scene>);
// throws user_error for an unknown option, a missing value or a missing scene.
// shared with simulate: to be replaced by the one option parser (support/ or cli/)
bench_options parse_arguments(const std::vector<std::string>& args);

} // namespace rotgen::bench
