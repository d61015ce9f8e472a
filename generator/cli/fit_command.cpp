// rotgen fit SCENE.yaml --data measured.csv --free KEY,... [--sigma COL=S,...] [-o fitted.yaml]
//            [--plot residuals.png] [--max-evaluations N] [--timings] [--quiet]
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "fit/fit.hpp"

#include <cstdlib>
#include <iostream>
#include <sstream>

namespace rotgen {

namespace {

const command_spec fit_command{
    "fit",
    "scene file",
    "SCENE.yaml --data measured.csv --free KEY,... [--sigma COL=S,...] [-o fitted.yaml] [--plot "
    "residuals.png] [--max-evaluations N] [--timings] [--quiet]",
    "Fits the free keys (initial.<name>, parameters.<name>, as sweep takes them) to measured\n"
    "columns by weighted least squares (Levenberg-Marquardt), the model's values at the\n"
    "measurement times from the run's dense output. Prints each key's estimate, standard error\n"
    "and initial guess, the correlation matrix, each column's RMS residual against its sigma,\n"
    "chi2 and its degrees of freedom, and why the solver stopped. A combination of keys the data\n"
    "do not determine (the condition number of the scaled J^T W J above 1e12) is refused with\n"
    "exit 2, naming it. A fit that does not converge exits 3, its last iterate in\n"
    "<output stem>.partial.yaml (fitted.partial.yaml without -o).\n\n"
    "example: rotgen fit top.yaml --data measured.csv --free parameters.I1,parameters.I2 "
    "--sigma omega1=1e-3,omega2=1e-3,omega3=1e-3 -o fitted.yaml",
    {{"--data",
      "FILE",
      "the measurements: CSV with a t column and recordable columns (omega1..3,\n"
      "                     q0..q3 together, angles, Lx.., ...) in any order; empty: missing",
      {}},
     {"--free", "KEYS", "the keys to fit, comma-separated (initial.<name>, parameters.<name>)", {}},
     {"--sigma",
      "COL=S,...",
      "each measured column's standard deviation (q: the attitude, radians);\n"
      "                     default: each column by its own residual RMS, the covariance\n"
      "                     scaled by the residual variance",
      {}},
     {"-o", "FILE", "the scene with the fitted values (covariance in a comment)", {"--output"}},
     {"--plot", "FILE", "the residuals against t, one panel per column: .png, .svg or .pdf", {}},
     {"--max-evaluations", "N", "of the residuals; default 100 (keys + 1)", {}},
     {"--timings", "", "print the wall time of each pipeline stage to standard error", {}},
     {"--quiet", "", "no summary (errors are still reported)", {"-q"}}}};

std::vector<std::string> split_keys(const std::string& text) {
    std::vector<std::string> keys;
    std::istringstream in(text);
    std::string k;
    while (std::getline(in, k, ','))
        if (!k.empty()) keys.push_back(k);
    return keys;
}

} // namespace

int cmd_fit(const std::vector<std::string>& args) {
    const parsed_options o = parse_options(fit_command, args);
    if (o.help) {
        std::cout << help_text(fit_command);
        return 0;
    }
    if (o.value("--data").empty()) usage_error(fit_command, "--data FILE is required");
    if (o.value("--free").empty()) usage_error(fit_command, "--free KEY,... is required");
    fit_request request;
    request.scene = o.operand;
    request.data = o.value("--data");
    request.free = split_keys(o.value("--free"));
    request.sigma = o.value("--sigma");
    request.output = o.value("-o");
    request.plot = o.value("--plot");
    const std::string n = o.value("--max-evaluations");
    if (!n.empty()) {
        char* end = nullptr;
        const long v = std::strtol(n.c_str(), &end, 10);
        if (*end != '\0' || v < 1 || v > 1000000)
            usage_error(fit_command, "--max-evaluations must be a whole number from 1 to 1e6");
        request.max_evaluations = static_cast<int>(v);
    }
    request.timings = o.has("--timings");
    request.quiet = o.has("--quiet");
    return fit(request);
}

} // namespace rotgen
