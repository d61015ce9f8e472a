// rotgen — running other programs: the C++ compiler, gnuplot, a compiled driver.
#pragma once

#include <string>

namespace rotgen {

// The C++ compiler: $CXX, else c++.
std::string compiler();
// s in single quotes for /bin/sh.
std::string shell_quote(const std::string& s);
// Runs a shell command, returns its stdout and stderr together; *status = its exit status.
std::string run_capture(const std::string& cmd, int* status);

} // namespace rotgen
