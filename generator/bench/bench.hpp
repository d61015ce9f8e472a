// rotgen bench: the work-precision report of one scene (generator/bench/bench.cpp).
#pragma once

#include <string>
#include <vector>

namespace rotgen {

// `rotgen bench ARGS...`; returns the exit status, throws user_error for bad input.
int cmd_bench(const std::vector<std::string>& args);

} // namespace rotgen
