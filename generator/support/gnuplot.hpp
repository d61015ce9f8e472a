// rotgen — drawing plots with gnuplot (Debian's gnuplot-nox), the one way both `simulate` and
// `bench` do it.
#pragma once

#include <string>

namespace rotgen {

class output_set; // support/atomic_file.hpp

// Runs the gnuplot `script`, which must `set output` to `output`'s temporary name given by
// `script_for(temporary)`, and renames the result into place only if gnuplot succeeded (or, given
// `outputs`, hands it to them: it appears with the command's other outputs).
// Throws user_error naming `output` (with gnuplot's first messages) when gnuplot fails.
//
//   draw_with_gnuplot("axis.png", [&](const std::string& file) {
//       return "set terminal pngcairo\nset output '" + file + "'\nplot sin(x)\n";
//   });
template <class ScriptFor>
void draw_with_gnuplot(const std::string& output, ScriptFor script_for,
                       output_set* outputs = nullptr);

// The same with the script text already made for the temporary `output + ".tmp<pid>"`.
void run_gnuplot(const std::string& output, const std::string& temporary, const std::string& script,
                 output_set* outputs = nullptr);

// Runs gnuplot on an existing script file that writes `temporary`, then renames `temporary` to
// `output`; the script stays (bench keeps its scripts beside its plots). user_error on failure.
void run_gnuplot_script(const std::string& script_path, const std::string& temporary,
                        const std::string& output, output_set* outputs = nullptr);

// A temporary name for `output` (beside it).
std::string gnuplot_temporary(const std::string& output);

template <class ScriptFor>
void draw_with_gnuplot(const std::string& output, ScriptFor script_for, output_set* outputs) {
    const std::string temporary = gnuplot_temporary(output);
    run_gnuplot(output, temporary, script_for(temporary), outputs);
}

// s with single quotes doubled, for a gnuplot single-quoted string.
std::string gnuplot_escape(const std::string& s);

} // namespace rotgen
