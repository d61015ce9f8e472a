#include "support/gnuplot.hpp"

#include "support/atomic_file.hpp"
#include "support/error.hpp"
#include "support/process.hpp"

#include <unistd.h>

#include <cstdio>

namespace rotgen {

std::string gnuplot_temporary(const std::string& output) {
    return output + ".tmp" + std::to_string(::getpid());
}

void run_gnuplot_script(const std::string& script_path, const std::string& temporary,
                        const std::string& output, output_set* outputs) {
    register_temporary(temporary);
    int status = 0;
    const std::string log = run_capture("gnuplot " + shell_quote(script_path), &status);
    if (status == 0 && outputs) { // the set renames it, or removes it
        outputs->add_file(temporary, output, output);
        return;
    }
    const bool drawn = status == 0 && std::rename(temporary.c_str(), output.c_str()) == 0;
    forget_temporary(temporary);
    if (!drawn) {
        std::remove(temporary.c_str());
        throw user_error({output}, "gnuplot failed to draw the plot (is gnuplot-nox installed?)" +
                                       (log.empty() ? std::string() : ": " + log.substr(0, 400)));
    }
}

void run_gnuplot(const std::string& output, const std::string& temporary, const std::string& script,
                 output_set* outputs) {
    const std::string script_path = temporary + ".gp";
    write_file_atomically(script_path, script);
    register_temporary(script_path);
    try {
        run_gnuplot_script(script_path, temporary, output, outputs);
    } catch (...) {
        std::remove(script_path.c_str());
        forget_temporary(script_path);
        throw;
    }
    std::remove(script_path.c_str());
    forget_temporary(script_path);
}

std::string gnuplot_escape(const std::string& s) {
    std::string r;
    for (char c : s)
        r += c == '\'' ? std::string("''") : std::string(1, c);
    return r;
}

} // namespace rotgen
