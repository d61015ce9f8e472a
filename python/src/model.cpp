// rotgen.Model: a model file read and checked (spec/), its derived equations (inspect/) and its
// header (the `rotgen emit` command itself, so that the header is the CLI's byte for byte).
#include "bindings.hpp"

#include "cli/commands.hpp"
#include "derive/derive.hpp"
#include "inspect/inspect.hpp"
#include "spec/spec.hpp"

#include <pybind11/stl.h>

#include <iostream>
#include <sstream>

namespace rotgen::python {

namespace {

// The model's name and parameters (name, default, description), read and checked now.
py::dict model_info(const std::string& path, const std::string& text) {
    std::string name;
    std::vector<std::tuple<std::string, double, std::string>> parameters;
    bool rotor = false;
    {
        symbolic_scope scope(path, text);
        const model_spec spec = load_model(path);
        name = spec.name;
        rotor = spec.rotor;
        for (const auto& p : spec.parameters)
            parameters.emplace_back(p.name, p.value, p.description);
    }
    py::dict d;
    d["name"] = name;
    d["parameters"] = parameters;
    d["rotor"] = rotor;
    return d;
}

output_format format_of(const std::string& f) {
    if (f == "text") return output_format::text;
    if (f == "latex") return output_format::latex;
    if (f == "json") return output_format::json;
    throw py::value_error("format must be 'text', 'latex' or 'json', not '" + f + "'");
}

// As `rotgen inspect MODEL [--format F] [--inertia]`: text and LaTeX with the inertia show the
// inertia report alone, which needs no derivation.
std::string inspect_model(const std::string& path, const std::string& text,
                          const std::string& format, bool inertia) {
    const output_format f = format_of(format);
    symbolic_scope scope(path, text);
    const model_spec spec = load_model(path);
    if (inertia && f != output_format::json) return inspect_inertia(spec, f, false);
    return inspect(spec, derive(spec), f, inertia, false);
}

// `rotgen emit` with these arguments; returns what it printed ("rotgen: wrote DIR/unit.hpp ...").
std::string emit_model(const std::vector<std::string>& args, const std::string& path,
                       const std::string& text) {
    std::ostringstream printed;
    symbolic_scope scope(path, text);
    std::streambuf* const saved = std::cout.rdbuf(printed.rdbuf());
    try {
        cmd_emit(args);
    } catch (...) {
        std::cout.rdbuf(saved);
        throw;
    }
    std::cout.rdbuf(saved);
    return printed.str();
}

} // namespace

void init_model(py::module_& m) {
    m.def("model_info", &model_info, py::arg("path"), py::arg("text") = "");
    m.def("inspect", &inspect_model, py::arg("path"), py::arg("text"), py::arg("format"),
          py::arg("inertia"));
    m.def("emit", &emit_model, py::arg("args"), py::arg("path"), py::arg("text"));
}

} // namespace rotgen::python
