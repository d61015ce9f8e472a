// rotgen — the command line: `rotgen --help` lists the commands, `rotgen <command> --help` each
// command's options.
//
// Exit status: 0 success; 2 input rejected, nothing written (one line
// "rotgen: error: FILE:LINE:COL: problem"); 3 a run that started but could not finish (its rows in
// <output>.partial.csv); 130 / 143 interrupted by SIGINT / SIGTERM, no temporary left behind;
// 1 an internal failure.
#include "cli/cli.hpp"
#include "support/atomic_file.hpp"

int main(int argc, char** argv) {
    rotgen::remove_temporaries_on_signal();
    return rotgen::run_cli(argc, argv);
}
