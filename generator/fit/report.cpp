#include "fit/report.hpp"

#include "simulate/plot.hpp"
#include "spec/spec.hpp"
#include "support/error.hpp"
#include "support/format.hpp"
#include "support/gnuplot.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <sstream>

namespace rotgen {

namespace {

std::string padded(const std::string& s, std::size_t width) {
    return s.size() >= width ? s + " " : s + std::string(width - s.size(), ' ');
}

std::string key_table(const fit_result& r) {
    std::size_t width = 4;
    for (const auto& k : r.keys)
        width = std::max(width, k.size() + 2);
    std::string out =
        padded("key", width) + padded("estimate", 18) + padded("stderr", 12) + "initial\n";
    for (std::size_t k = 0; k < r.keys.size(); ++k) {
        const auto i = static_cast<Eigen::Index>(k);
        out += padded(r.keys[k], width) + padded(short_number(r.values[i], 10), 18) +
               padded(short_number(r.stderrs[i]), 12) + format_double(r.initial[i]) + "\n";
    }
    return out;
}

std::string correlation_table(const fit_result& r) {
    std::string out = "correlation (rows and columns in the order of the keys):\n";
    for (Eigen::Index i = 0; i < r.correlation.rows(); ++i) {
        out += " ";
        for (Eigen::Index j = 0; j < r.correlation.cols(); ++j) {
            char buf[16];
            std::snprintf(buf, sizeof buf, " %+.3f", r.correlation(i, j));
            out += buf;
        }
        out += "\n";
    }
    return out;
}

std::string column_table(const fit_result& r) {
    std::string out = "residuals (model - measured)" +
                      std::string(r.sigma_given ? ", sigma from --sigma:\n"
                                                : ", sigma = each column's own residual RMS (no "
                                                  "--sigma):\n");
    out += "  " + padded("column", 12) + padded("count", 8) + padded("RMS", 12) +
           padded("sigma", 12) + "RMS/sigma\n";
    for (std::size_t c = 0; c < r.columns.size(); ++c)
        out += "  " + padded(r.columns[c], 12) + padded(std::to_string(r.count[c]), 8) +
               padded(short_number(r.rms[c]), 12) + padded(short_number(r.sigma[c]), 12) +
               short_number(r.rms[c] / r.sigma[c]) + "\n";
    return out;
}

} // namespace

std::string fit_summary(const fit_result& r, const std::string& data_file) {
    std::string out = std::string(r.converged ? "fitted " : "NOT CONVERGED: ") +
                      std::to_string(r.keys.size()) + " keys to " + data_file + "\n";
    out += key_table(r) + correlation_table(r) + column_table(r);
    out += "chi2 " + short_number(r.chi2, 6) + " with " + std::to_string(r.dof) +
           " degrees of freedom (chi2/dof " + short_number(r.chi2 / double(r.dof)) + ")";
    out += r.sigma_given ? "; covariance from the given sigmas\n"
                         : "; covariance scaled by the residual variance chi2/dof\n";
    out += std::to_string(r.iterations) + " iterations, " + std::to_string(r.evaluations) +
           " evaluations, " + std::to_string(r.jacobians) + " Jacobians " +
           (r.sensitivities ? "from the sensitivities (" : "by central differences (") +
           std::to_string(r.runs) + " runs); stopped: " + r.stop + "\n";
    out += "condition number of the scaled J^T W J: " + short_number(r.condition) + "\n";
    return out;
}

std::string fitted_scene(const scene_spec& scene, const fit_result& r, const std::string& output) {
    YAML::Node root = load_yaml_file(scene.file);
    bool parameter_free = false;
    for (std::size_t k = 0; k < r.keys.size(); ++k) {
        const std::string& key = r.keys[k];
        const std::string name = key.substr(key.find('.') + 1);
        const double v = r.values[static_cast<Eigen::Index>(k)];
        if (key.rfind("parameters.", 0) == 0) root["parameters"][name] = format_double(v);
        parameter_free = parameter_free || key.rfind("parameters.", 0) == 0;
        if (key.rfind("initial.", 0) == 0) root["initial"][name] = format_double(v);
    }
    const auto& q = scene.model.angles.names;
    for (auto item : root["initial"]) { // the numbers the fit ran with
        const std::string name = item.first.Scalar();
        for (std::size_t i = 0; parameter_free && i < 3; ++i)
            if (name == q[i]) item.second = format_double(scene.angles[i]);
        for (std::size_t i = 0; parameter_free && i < 3; ++i)
            if (name != q[i] && name.find(q[i]) != std::string::npos)
                item.second = format_double(scene.initial_rates[i]);
        if (parameter_free && name.rfind("omega", 0) == 0)
            item.second =
                format_double(scene.initial_rates[static_cast<std::size_t>(name[5] - '1')]);
    }
    namespace fs = std::filesystem;
    if (root["model"] && root["model"].IsScalar() && fs::exists(scene.file)) {
        const fs::path model =
            fs::absolute(fs::path(scene.file).parent_path() / root["model"].Scalar());
        const fs::path dir = fs::absolute(fs::path(output)).parent_path();
        root["model"] = model.lexically_normal().lexically_relative(dir).string();
    }
    std::ostringstream text;
    text << "# rotgen fit: " << scene.file << " fitted (chi2 " << short_number(r.chi2, 6) << ", "
         << r.dof << " degrees of freedom" << (r.converged ? "" : "; NOT CONVERGED: last iterate")
         << ")\n# covariance of";
    for (const auto& k : r.keys)
        text << " " << k;
    text << ":\n";
    for (Eigen::Index i = 0; i < r.covariance.rows(); ++i) {
        text << "#  ";
        for (Eigen::Index j = 0; j < r.covariance.cols(); ++j)
            text << " " << format_double(r.covariance(i, j));
        text << "\n";
    }
    YAML::Emitter out;
    out << root;
    text << out.c_str() << "\n";
    return text.str();
}

void plot_residuals(const std::string& file, const fit_result& r, output_set& outputs) {
    const std::size_t panels = r.columns.size();
    draw_with_gnuplot(
        file,
        [&](const std::string& temporary) {
            std::ostringstream s;
            s << "set terminal " << plot_terminal(file, panels) << "\nset output '"
              << gnuplot_escape(temporary) << "'\n$residuals << EOD\n";
            for (std::size_t i = 0; i < r.t.size(); ++i) {
                s << format_double(r.t[i]);
                for (std::size_t c = 0; c < panels; ++c) {
                    const double v =
                        r.residuals(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c));
                    s << " " << (std::isnan(v) ? std::string("NaN") : format_double(v));
                }
                s << "\n";
            }
            s << "EOD\nset datafile missing 'NaN'\nset multiplot layout " << panels
              << ",1 title 'residuals (model - measured)'\nset grid\nset key off\n";
            for (std::size_t c = 0; c < panels; ++c)
                s << "set ylabel '" << gnuplot_escape(r.columns[c]) << "'\n"
                  << (c + 1 == panels ? "set xlabel 't'\n" : "")
                  << "plot $residuals using 1:" << c + 2 << " with points pt 7 ps 0.4, "
                  << r.sigma[c] << " with lines dt 2, " << -r.sigma[c] << " with lines dt 2\n";
            s << "unset multiplot\n";
            return s.str();
        },
        &outputs);
}

} // namespace rotgen
