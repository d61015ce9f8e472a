// rotgen bench: where the harness (bench/workprecision) and the runtime headers are.
#pragma once

#include <filesystem>
#include <vector>

namespace rotgen::bench {

struct bench_sources {
    std::filesystem::path harness, runtime;
};

// $ROTGEN_SOURCE_DIR (a source tree) when set, and then that tree or a user_error; else the
// installed layout next to this executable (<prefix>/share/rotgen/bench/workprecision and
// <prefix>/include/rotgen/runtime); else the source tree this file was compiled from (a build
// tree). Throws user_error when none has harness.hpp and rotgen.hpp.
bench_sources find_bench_sources();

// The first of `candidates` that has harness.hpp and rotgen.hpp; throws the user_error "rotgen
// bench: cannot find the harness ...; looked in H1, H2; set ROTGEN_SOURCE_DIR ..." when none has.
// (A build's own source tree is always a candidate, so from `rotgen bench` this error is reached
// only when that tree has been moved or deleted; the tests call this function directly.)
bench_sources first_complete(const std::vector<bench_sources>& candidates);

} // namespace rotgen::bench
