// rotgen simulate — the plot of a run: one panel per kind of quantity (angles, rates, momenta,
// body angular velocity, body axes, energy drift), against t, drawn by gnuplot into a PNG.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace rotgen {

// The gnuplot terminal for a plot file by its extension (.png, .svg, .pdf), for a figure of
// `panels` panels. Throws user_error naming the file for any other extension.
std::string plot_terminal(const std::string& file, std::size_t panels);

// `csv`: the samples (t first, then the columns of `record` in order; may be a temporary file).
// `energy0`: the energy at the start; its panel shows energy - energy(0), the drift.
void plot_run(const std::string& png, const std::string& csv,
              const std::vector<std::string>& record, const std::string& title, double energy0);

} // namespace rotgen
