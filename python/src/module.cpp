// _rotgen: the compiled core of the `rotgen` Python package (python/rotgen/). One file per stage
// it exposes; each binding calls the library functions the commands in generator/cli/ call.
#include "bindings.hpp"

#include "run/prepared.hpp"
#include "support/memory_files.hpp"

namespace rotgen::python {

symbolic_scope::symbolic_scope(const std::string& path, const std::string& text)
    : m_lock(symbolic_mutex()), m_path(path) {
    if (!text.empty()) {
        set_memory_file(path, text);
        m_registered = true;
    }
}

symbolic_scope::~symbolic_scope() {
    if (m_registered) erase_memory_file(m_path);
}

bool signal_check::interrupted() {
    m_last = std::chrono::steady_clock::now();
    if (m_raised) return true;
    py::gil_scoped_acquire gil;
    m_raised = PyErr_CheckSignals() != 0;
    return m_raised;
}

} // namespace rotgen::python

PYBIND11_MODULE(_rotgen, m) {
    m.doc() = "rotgen's compiled core: the run, sweep, inspect and emit stages (use `rotgen`)";
    m.attr("version") = ROTGEN_VERSION;
    rotgen::python::init_errors(m);
    rotgen::python::init_model(m);
    rotgen::python::init_simulate(m);
    rotgen::python::init_sweep(m);
}
