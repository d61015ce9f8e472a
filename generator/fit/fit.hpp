// rotgen fit — a model fitted to measurements:
//
//   rotgen fit SCENE.yaml --data measured.csv --free parameters.I1,initial.omega1
//              [--sigma omega1=1e-3,q=2e-4] [-o fitted.yaml] [--plot residuals.png]
//
// The free keys (`initial.<name>`, `parameters.<name>`, as `sweep` takes them) are fitted by
// weighted least squares (fit/solve.hpp) to the measured columns (fit/data.hpp), the model's values
// at the measurement times coming from the run's dense output. Exit 2 (nothing written) for bad
// data or keys and for a problem the data do not determine; exit 3 when the solver does not
// converge, the last iterate in `<output stem>.partial.yaml` (`fitted.partial.yaml` without -o).
#pragma once

#include "fit/data.hpp"
#include "fit/solve.hpp"
#include "scene/scene.hpp"
#include "support/timings.hpp"

#include <string>
#include <vector>

namespace rotgen {

struct fit_request {
    std::string scene, data;       // the files
    std::vector<std::string> free; // the keys, as written
    std::string sigma;             // "omega1=1e-3,q=2e-4"; empty: each column by its residual RMS
    std::string output;            // the fitted scene; empty: not written
    std::string plot;              // the residuals against t; empty: none
    int max_evaluations = 0;       // of the residuals; 0: 100 (keys + 1)
    bool quiet = false, timings = false;
};

// The sigmas of the residual columns from `--sigma` text (a column name, or `q` for the
// attitude); empty text gives none. user_error at `where` for a malformed entry, a column that is
// not measured, a measured column without a sigma.
std::vector<double> parse_sigma(const std::string& text, const std::vector<std::string>& names,
                                const source_location& where);

// The fit itself, writing nothing: what `rotgen fit` and Python's rotgen.fit share.
fit_result fit_scene(const scene_spec& scene, const measured_data& data,
                     const std::vector<std::string>& free, const std::string& sigma,
                     int max_evaluations, stage_timings& timings);

// Returns the exit status; throws user_error for bad input (nothing written then).
int fit(const fit_request& request);

} // namespace rotgen
