#include "simulate/plot.hpp"

#include "scene/scene.hpp"
#include "support/error.hpp"
#include "support/format.hpp"
#include "support/gnuplot.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <utility>

namespace rotgen {

namespace {

using panel_list = std::vector<std::pair<std::string, std::vector<std::string>>>;

// The panel a recorded quantity goes into (a drift: its own panel of drifts).
std::string panel_of(const std::string& name, bool drift) {
    if (drift) return name == "energy" ? "energy - energy(0)" : "conserved momenta - value at t0";
    if (name == "phi" || name == "theta" || name == "psi") return "angles (rad)";
    if (name.size() > 4 && name.substr(name.size() - 4) == "_dot") return "angle rates (rad/time)";
    if (name.rfind("p_", 0) == 0) return "momenta";
    if (name.rfind("omega", 0) == 0) return "body angular velocity";
    if (name.rfind("body_", 0) == 0) return "body axis " + name.substr(5) + " in space";
    return name;
}

// One panel per kind of quantity, in the order first recorded; each with its gnuplot plot terms.
panel_list panels_of(const std::string& csv, const std::vector<std::string>& record,
                     const std::map<std::string, double>& drifts) {
    panel_list panels;
    int column = 2;
    for (const auto& name : record) {
        const auto drift = drifts.find(name);
        const std::string p = panel_of(name, drift != drifts.end());
        auto it =
            std::find_if(panels.begin(), panels.end(), [&](const auto& x) { return x.first == p; });
        if (it == panels.end()) it = panels.insert(panels.end(), {p, {}});
        for (const auto& c : record_columns(name)) {
            const std::string col = std::to_string(column++);
            it->second.push_back("'" + csv + "' using 1:" +
                                 (drift == drifts.end()
                                      ? col + " with lines title '" + c + "'"
                                      : "($" + col + " - (" + format_number(drift->second) +
                                            ")) with lines title '" + c + " - " + c + "(0)'"));
        }
    }
    return panels;
}

} // namespace

std::string plot_terminal(const std::string& file, std::size_t panels) {
    const std::size_t dot = file.rfind('.');
    std::string ext = dot == std::string::npos ? "" : file.substr(dot + 1);
    for (char& c : ext)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const std::size_t height =
        120 + 260 * panels; // pixels (PNG, SVG); PDF: the same at 100 per inch
    if (ext == "png") return "pngcairo size 1000," + std::to_string(height) + " noenhanced";
    if (ext == "svg") return "svg size 1000," + std::to_string(height) + " noenhanced";
    if (ext == "pdf")
        return "pdfcairo size 10in," + std::to_string(height / 100.0).substr(0, 4) +
               "in noenhanced";
    throw user_error({file}, "cannot tell the plot format from the extension '" +
                                 (ext.empty() ? "" : "." + ext) +
                                 "' (expected .png, .svg or .pdf)");
}

std::string plot_script(const std::string& output, const std::string& terminal_for,
                        const std::string& csv, const std::vector<std::string>& record,
                        const std::string& title, const std::map<std::string, double>& drifts,
                        const std::vector<double>& marks) {
    const panel_list panels = panels_of(csv, record, drifts);
    std::ostringstream script;
    script << "set terminal " << plot_terminal(terminal_for, panels.size()) << "\n"
           << "set output '" << output << "'\n"
           << "set datafile separator ','\nset key outside right\nset grid\n"
           // the same margins in every panel: their time axes line up
           << "set lmargin at screen 0.11\nset rmargin at screen 0.76\n"
           << "set multiplot layout " << panels.size() << ",1 title '" << title << "'\n";
    for (double t : marks) // the actions' times, in every panel
        script << "set arrow from " << format_number(t) << ", graph 0 to " << format_number(t)
               << ", graph 1 nohead dashtype 2 linecolor rgb 'gray40'\n";
    for (std::size_t i = 0; i < panels.size(); ++i) {
        script << "set ylabel '" << panels[i].first << "'\n";
        script << (i + 1 == panels.size() ? "set xlabel 't'\n" : "unset xlabel\n");
        script << "plot ";
        for (std::size_t j = 0; j < panels[i].second.size(); ++j)
            script << (j ? ", " : "") << panels[i].second[j];
        script << "\n";
    }
    script << "unset multiplot\n";
    return script.str();
}

void plot_run(const std::string& png, const std::string& csv,
              const std::vector<std::string>& record, const std::string& title,
              const std::map<std::string, double>& drifts, output_set* outputs,
              const std::vector<double>& marks) {
    draw_with_gnuplot(
        png,
        [&](const std::string& output) {
            return plot_script(output, png, csv, record, title, drifts, marks);
        },
        outputs);
}

} // namespace rotgen
