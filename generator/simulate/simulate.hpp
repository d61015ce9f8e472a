// rotgen simulate: integrate one scene and record it (simulate_command.cpp).
#pragma once

#include <string>
#include <vector>

namespace rotgen {

// `rotgen simulate ARGS...`; returns the exit status, throws user_error for bad input.
int cmd_simulate(const std::vector<std::string>& args);

} // namespace rotgen
