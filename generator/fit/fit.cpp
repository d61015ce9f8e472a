#include "fit/fit.hpp"

#include "expr/numbers.hpp"
#include "fit/model.hpp"
#include "fit/report.hpp"
#include "fit/residuals.hpp"
#include "run/prepared.hpp"
#include "simulate/plot.hpp"
#include "support/atomic_file.hpp"
#include "support/error.hpp"
#include "support/output_paths.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>

namespace rotgen {

std::vector<double> parse_sigma(const std::string& text, const std::vector<std::string>& names,
                                const source_location& where) {
    if (text.empty()) return {};
    std::map<std::string, double> given;
    std::istringstream in(text);
    std::string entry;
    while (std::getline(in, entry, ',')) {
        const auto eq = entry.find('=');
        const std::string name = entry.substr(0, eq);
        const std::string value = eq == std::string::npos ? "" : entry.substr(eq + 1);
        if (eq == std::string::npos || !is_decimal(value))
            throw user_error(where, "'" + entry + "': expected COLUMN=SIGMA (a number)");
        const double s = std::strtod(value.c_str(), nullptr);
        if (!(s > 0) || !std::isfinite(s))
            throw user_error(where, "sigma of '" + name + "' must be a positive number");
        if (std::find(names.begin(), names.end(), name) == names.end()) {
            const std::string best = closest_name(name, names);
            throw user_error(where, "'" + name + "' is not a measured column (q for the attitude)" +
                                        (best.empty() ? "" : "; did you mean '" + best + "'?"));
        }
        given[name] = s;
    }
    std::vector<double> sigma;
    for (const auto& n : names) {
        if (!given.count(n))
            throw user_error(where, "no sigma for the measured column '" + n + "'; give " + n +
                                        "=SIGMA (or leave out --sigma to weight each column by "
                                        "its own residual RMS)");
        sigma.push_back(given[n]);
    }
    return sigma;
}

fit_result fit_scene(const scene_spec& scene, const measured_data& data,
                     const std::vector<std::string>& free, const std::string& sigma,
                     int max_evaluations, stage_timings& timings) {
    std::string joined;
    for (const auto& k : free)
        joined += (joined.empty() ? "" : ",") + k;
    const source_location free_where{"rotgen fit --free " + joined};
    std::vector<fit_key> keys;
    {
        const std::lock_guard<std::mutex> lock(symbolic_mutex());
        keys = resolve_free(scene, free, free_where);
    }
    const fit_model model(scene, data, std::move(keys), timings);
    const fit_residuals res(data, model);
    const std::vector<double> sigmas =
        parse_sigma(sigma, res.sigma_names(), {"rotgen fit --sigma " + sigma});
    const int evaluations =
        max_evaluations > 0 ? max_evaluations : 100 * (static_cast<int>(free.size()) + 1);
    return solve_fit(model, res, model.start(), sigmas, free_where, evaluations);
}

namespace {

// fitted.yaml -> fitted.partial.yaml; none -> fitted.partial.yaml.
std::string partial_name(const std::string& output) {
    if (output.empty() || output == "-") return "fitted.partial.yaml";
    const auto dot = output.rfind('.'), slash = output.rfind('/');
    const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
    return (has_ext ? output.substr(0, dot) : output) + ".partial.yaml";
}

// The last iterate to the partial file; exit 3.
int not_converged(const fit_request& q, const scene_spec& scene, const fit_result& r,
                  const std::vector<std::string>& inputs, std::ostream& out) {
    const std::string partial = partial_name(q.output);
    atomic_file file(partial, inputs);
    file.stream() << fitted_scene(scene, r, partial);
    file.commit();
    out << "the fit did not converge (" << r.stop << "): its last iterate is in " << partial
        << "\n";
    std::cerr << "rotgen: error: " << q.data << ": the fit did not converge (" << r.stop
              << "); last iterate in " << partial << "\n";
    return 3;
}

} // namespace

int fit(const fit_request& q) {
    const scene_spec scene = load_scene(q.scene, "fit");
    const std::vector<std::string> inputs{q.scene, scene.model.file, q.data};
    std::vector<named_file> outputs_named;
    if (!q.output.empty()) outputs_named.push_back({q.output, "-o"});
    if (!q.plot.empty()) outputs_named.push_back({q.plot, "--plot"});
    check_distinct_files(outputs_named, {{q.scene, "the scene"}, {q.data, "--data"}});
    if (!q.plot.empty()) plot_terminal(q.plot, 1);
    if (!q.plot.empty()) atomic_file probe(q.plot, inputs);
    std::optional<atomic_file> yaml_out;
    if (!q.output.empty()) yaml_out.emplace(q.output, inputs);
    const measured_data data = read_measured(q.data, scene);

    stage_timings timings;
    const fit_result r = timings.time("fit", q.data, [&] {
        return fit_scene(scene, data, q.free, q.sigma, q.max_evaluations, timings);
    });
    std::ostream& out = is_standard_output(q.output) ? std::cerr : std::cout;
    if (!q.quiet) out << fit_summary(r, q.data);
    if (!r.converged) return not_converged(q, scene, r, inputs, out);
    output_set outputs;
    if (yaml_out) {
        yaml_out->stream() << fitted_scene(scene, r, q.output);
        yaml_out->commit(outputs);
    }
    if (!q.plot.empty()) plot_residuals(q.plot, r, outputs);
    outputs.commit();
    if (!q.quiet && yaml_out) out << "  wrote   " << q.output << " (the fitted scene)\n";
    if (!q.quiet && !q.plot.empty()) out << "  wrote   " << q.plot << " (the residuals)\n";
    if (q.timings) timings.print(std::cerr);
    return 0;
}

} // namespace rotgen
