// rotgen bench: where the harness (bench/workprecision) and the runtime headers are.
#pragma once

#include <filesystem>

namespace rotgen::bench {

struct bench_sources {
    std::filesystem::path harness, runtime;
};

// $ROTGEN_SOURCE_DIR (a source tree) when set, and then that tree or a user_error; else the
// installed layout next to this executable (<prefix>/share/rotgen/bench/workprecision and
// <prefix>/include/rotgen/runtime); else the source tree this file was compiled from (a build
// tree). Throws user_error when none has harness.hpp and rotgen.hpp.
bench_sources find_bench_sources();

} // namespace rotgen::bench
