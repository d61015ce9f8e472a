// rotgen simulate — the textbook figures of a run (chapter section 5.6):
//
//   --plot-axis FILE     the path of the figure axis's tip (the body z axis; a rotor's line) on
//                        the unit sphere: seen from above, and as its polar angle against its
//                        azimuth, where a heavy top's loops, cusps and waves show (5.6.1);
//   --plot-polhode FILE  the polhode: the path of the body angular velocity ω in the body frame,
//                        on the energy ellipsoid ω·Iω = 2T and the momentum ellipsoid |Iω|² = L²
//                        (5.6.3).
//
// Each figure's data are written beside it, in FILE with its extension replaced by .axis.csv or
// .polhode.csv, so that what is drawn can be checked and redrawn. The run records what a figure
// needs (body_z, or a rotor's phi and theta; omega and L) beside the scene's own columns, which
// the CSV keeps unchanged.
#pragma once

#include "run/engine.hpp"
#include "scene/scene.hpp"

#include <string>
#include <vector>

namespace rotgen {

class output_set; // support/atomic_file.hpp

struct figure_request {
    std::string axis;    // --plot-axis FILE; empty: none
    std::string polhode; // --plot-polhode FILE; empty: none
};

// The data file of a figure: FILE with its extension replaced by .<kind>.csv (axis, polhode).
std::string figure_data_path(const std::string& figure, const std::string& kind);

// Refuses (user_error, exit 2) a figure the scene cannot draw (the polhode of a rotor), or a
// figure file whose extension gnuplot cannot write; checked before any work.
void check_figures(const figure_request& q, const scene_spec& scene);

// The scene's records plus what the figures need.
std::vector<std::string> figure_records(const figure_request& q, const scene_spec& scene);

// Draws the axis figure and writes its data from a run that recorded figure_records; both appear
// with `outputs` (support/atomic_file.hpp). The data file starts with `provenance` (a line).
void draw_axis_figure(const std::string& file, const scene_spec& scene, const run_result& run,
                      const std::vector<std::string>& inputs, const std::string& provenance,
                      output_set& outputs);

// The same for the polhode.
void draw_polhode(const std::string& file, const scene_spec& scene, const run_result& run,
                  const std::vector<std::string>& inputs, const std::string& provenance,
                  output_set& outputs);

} // namespace rotgen
