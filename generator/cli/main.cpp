// rotgen — the command line.
//
//   rotgen inspect MODEL.yaml [--format text|latex|json]
//
// Exit status: 0 success, 2 user error (one line "rotgen: error: FILE:LINE:COL: problem"),
// 1 internal failure.
#include "cli/cli.hpp"

int main(int argc, char** argv) { return rotgen::run_cli(argc, argv); }
