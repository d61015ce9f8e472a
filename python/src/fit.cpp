// rotgen.fit: the scene's free keys fitted to measurements (fit/fit.hpp), as `rotgen fit` fits
// them, the data given as columns (a DataFrame's) instead of a CSV file.
#include "bindings.hpp"

#include "fit/fit.hpp"
#include "fit/report.hpp"
#include "scene/scene.hpp"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>

namespace rotgen::python {

namespace {

py::dict result_of(const fit_result& r, const std::string& fitted_yaml) {
    py::dict d;
    d["keys"] = r.keys;
    d["initial"] = r.initial;
    d["values"] = r.values;
    d["stderr"] = r.stderrs;
    d["covariance"] = r.covariance;
    d["correlation"] = r.correlation;
    d["columns"] = r.columns;
    d["sigma_names"] = r.sigma_names;
    d["sigma"] = r.sigma;
    d["rms"] = r.rms;
    d["count"] = r.count;
    d["sigma_given"] = r.sigma_given;
    d["variance_scale"] = r.variance_scale;
    d["chi2"] = r.chi2;
    d["dof"] = r.dof;
    d["iterations"] = r.iterations;
    d["evaluations"] = r.evaluations;
    d["jacobians"] = r.jacobians;
    d["runs"] = r.runs;
    d["sensitivities"] = r.sensitivities;
    d["condition"] = r.condition;
    d["stop"] = r.stop;
    d["converged"] = r.converged;
    d["t"] = r.t;
    d["residuals"] = r.residuals;
    d["fitted_yaml"] = fitted_yaml;
    d["summary"] = fit_summary(r, "the data");
    return d;
}

// The scene read and the data checked (a CSV file `data_path`, or the columns) under the lock; the
// fit's own preparation and runs outside it (a member's run takes the lock where it uses GiNaC,
// run/prepared.hpp), then the fitted scene written and the scene destroyed under it again.
// `names`/`columns`: the data, NaN missing.
py::dict fit_scene_columns(const std::string& path, const std::string& text,
                           const std::string& data_path, const std::vector<std::string>& names,
                           const std::vector<std::vector<double>>& columns,
                           const std::vector<std::string>& free, const std::string& sigma,
                           int max_evaluations) {
    std::unique_ptr<scene_spec> scene;
    std::unique_ptr<measured_data> data;
    {
        symbolic_scope scope(path, text);
        scene = std::make_unique<scene_spec>(load_scene(path, "fit"));
        data = std::make_unique<measured_data>(
            data_path.empty() ? measured_from_columns(names, columns, *scene, "<data>")
                              : read_measured(data_path, *scene));
    }
    fit_result r;
    std::string fitted;
    try {
        py::gil_scoped_release released;
        stage_timings timings;
        r = fit_scene(*scene, *data, free, sigma, max_evaluations, timings);
    } catch (...) {
        symbolic_scope scope(path, "");
        scene.reset();
        throw;
    }
    {
        symbolic_scope scope(path, text); // the GIL released: no Python object in here
        fitted = fitted_scene(*scene, r, "fitted.yaml");
        scene.reset();
    }
    return result_of(r, fitted);
}

} // namespace

void init_fit(py::module_& m) {
    m.def("fit", &fit_scene_columns, py::arg("path"), py::arg("text"), py::arg("data_path"),
          py::arg("names"), py::arg("columns"), py::arg("free"), py::arg("sigma") = "",
          py::arg("max_evaluations") = 0);
}

} // namespace rotgen::python
