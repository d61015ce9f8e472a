// rotgen simulate — the plot of a run: one panel per kind of quantity (angles, rates, momenta,
// body angular velocity, body axes, energy drift), against t, drawn by gnuplot into a PNG.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace rotgen {

class output_set; // support/atomic_file.hpp

// The gnuplot terminal for a plot file by its extension (.png, .svg, .pdf), for a figure of
// `panels` panels. Throws user_error naming the file for any other extension.
std::string plot_terminal(const std::string& file, std::size_t panels);

// `csv`: the samples (t first, then the columns of `record` in order; may be a temporary file).
// `drifts`: the quantities drawn as their change from the start, with their value at the start:
// the energy and the conserved momenta (their raw values would fill the axis with ticks that all
// read the same). Every panel has the same margins, so that their time axes line up. `marks`: the
// times of the run's actions (events that act), drawn in every panel as dashed vertical lines.
// Given `outputs`, the plot appears with them (support/atomic_file.hpp's output_set).
void plot_run(const std::string& png, const std::string& csv,
              const std::vector<std::string>& record, const std::string& title,
              const std::map<std::string, double>& drifts, output_set* outputs = nullptr,
              const std::vector<double>& marks = {});

// The gnuplot script plot_run runs, writing `output`.
std::string plot_script(const std::string& output, const std::string& terminal_for,
                        const std::string& csv, const std::vector<std::string>& record,
                        const std::string& title, const std::map<std::string, double>& drifts,
                        const std::vector<double>& marks = {});

} // namespace rotgen
