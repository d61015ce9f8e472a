// rotgen fit — what a fit shows and writes: the summary (each free key with its estimate, standard
// error and initial guess; the correlation matrix; each column's RMS residual against its sigma;
// chi2 and degrees of freedom; iterations and why the solver stopped), the fitted scene (the scene
// file with the fitted values written in and the covariance in a comment, so that `rotgen simulate`
// runs the fitted motion), and the residual plot.
#pragma once

#include "fit/solve.hpp"
#include "scene/scene.hpp"

#include <string>

namespace rotgen {

class output_set; // support/atomic_file.hpp

std::string fit_summary(const fit_result& r, const std::string& data_file);

// The scene file's YAML with the fitted values: each free parameter in `parameters:`, each free
// initial value in `initial:`, and, when a parameter is free, every initial value as the number
// the fit ran with (a parameter key holds the other initial values at their numbers). A model
// given by path is referred to from `output`'s folder.
std::string fitted_scene(const scene_spec& scene, const fit_result& r, const std::string& output);

// The residuals against t, one panel per residual column (gnuplot: .png, .svg or .pdf).
void plot_residuals(const std::string& file, const fit_result& r, output_set& outputs);

} // namespace rotgen
