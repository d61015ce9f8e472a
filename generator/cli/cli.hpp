// rotgen — command-line dispatch (kept apart from main() so tests can drive it).
#pragma once

namespace rotgen {

// Runs `rotgen ARGS...`; prints results to stdout, diagnostics to stderr; returns the exit status.
int run_cli(int argc, char** argv);

} // namespace rotgen
