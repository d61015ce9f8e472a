// rotgen's Python module (_rotgen): what the binding files share.
//
// GiNaC is not thread-safe (run/prepared.hpp): every binding does its symbolic work (reading a
// model or scene, deriving, building forms, destroying what holds GiNaC objects) inside a
// `symbolic_scope`, which releases the GIL, then holds symbolic_mutex(), the lock the members of a
// sweep already take. No Python object keeps a GiNaC object: a Model or Scene keeps its path (or
// its text) and is read again when it is used.
#pragma once

#include <pybind11/pybind11.h>

#include <chrono>
#include <mutex>
#include <string>

namespace rotgen::python {

namespace py = pybind11;

// The GIL released, symbolic_mutex() held, and `text` (when not empty) registered as the content of
// `path` (support/memory_files.hpp) for as long as the scope lives.
class symbolic_scope {
  public:
    symbolic_scope(const std::string& path, const std::string& text);
    symbolic_scope(const symbolic_scope&) = delete;
    symbolic_scope& operator=(const symbolic_scope&) = delete;
    ~symbolic_scope();

  private:
    py::gil_scoped_release m_released;
    std::unique_lock<std::mutex> m_lock;
    std::string m_path;
    bool m_registered = false;
};

// Thrown (as a C++ exception, through the engine) when Ctrl-C was seen: the Python error is set,
// and the binding raises it once the GIL is back.
struct interrupted {};

// Called on the thread that holds no GIL, while members integrate: every `period` it takes the
// GIL and runs the Python signal handlers (PyErr_CheckSignals); true once one raised.
class signal_check {
  public:
    bool due() const { return std::chrono::steady_clock::now() - m_last >= period; }
    bool interrupted();

  private:
    static constexpr std::chrono::milliseconds period{5};
    std::chrono::steady_clock::time_point m_last = std::chrono::steady_clock::now();
    bool m_raised = false;
};

void init_errors(py::module_& m);
void init_model(py::module_& m);
void init_simulate(py::module_& m);
void init_sweep(py::module_& m);

} // namespace rotgen::python
