// rotgen — the command line: `rotgen --help` lists the commands, `rotgen <command> --help` each
// command's options.
//
// Exit status: 0 success; 2 input rejected, nothing written (one line
// "rotgen: error: FILE:LINE:COL: problem"; also a standard output that could not be written:
// "rotgen: error: standard output: cannot write: No space left on device"); 3 a run that started
// but could not finish (its rows in <output>.partial.csv); 130 / 143 interrupted by SIGINT /
// SIGTERM, no temporary left behind; 141 the reader of standard output went away (quietly);
// 1 an internal failure.
#include "cli/cli.hpp"
#include "support/atomic_file.hpp"
#include "support/standard_output.hpp"

#include <unistd.h>

#include <iostream>
#include <optional>

int main(int argc, char** argv) {
    rotgen::remove_temporaries_on_signal();
    // Every write to standard output checked (support/standard_output.hpp); a terminal keeps the
    // usual line-buffered stream.
    std::optional<rotgen::checked_output_buffer> checked;
    std::streambuf* usual = nullptr;
    if (!::isatty(1)) usual = std::cout.rdbuf(&checked.emplace(1));
    const int status = rotgen::run_cli(argc, argv);
    if (usual) std::cout.rdbuf(usual); // `checked` writes what is left as it goes
    return status;
}
