// rotgen — the sub-commands behind the CLI (cli.cpp dispatches). Each parses the arguments after
// the command name with the one option parser (options.hpp), calls the stage that does the work,
// and returns the exit status; user errors are thrown as user_error (cli.cpp prints them and
// returns 2).
#pragma once

#include <string>
#include <vector>

namespace rotgen {

int cmd_inspect(const std::vector<std::string>& args);  // inspect_command.cpp
int cmd_emit(const std::vector<std::string>& args);     // emit_command.cpp
int cmd_simulate(const std::vector<std::string>& args); // simulate_command.cpp
int cmd_bench(const std::vector<std::string>& args);    // bench_command.cpp
int cmd_sweep(const std::vector<std::string>& args);    // sweep_command.cpp
int cmd_view(const std::vector<std::string>& args);     // view_command.cpp
int cmd_tune(const std::vector<std::string>& args);     // tune_command.cpp
int cmd_fit(const std::vector<std::string>& args);      // fit_command.cpp

} // namespace rotgen
