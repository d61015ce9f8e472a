// rotgen's Python module (_rotgen): what the binding files share.
//
// GiNaC is not thread-safe (run/prepared.hpp): every binding does its symbolic work (reading a
// model or scene, deriving, building forms, destroying what holds GiNaC objects) inside a
// `symbolic_scope`, which releases the GIL, then holds symbolic_mutex(), the lock the members of a
// sweep already take. No Python object keeps a GiNaC object: a Model or Scene keeps its path (or
// its text) and is read again when it is used.
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <functional>
#include <mutex>
#include <string>

namespace rotgen {
struct scene_spec;
enum class auto_use : int; // tune/tune.hpp
} // namespace rotgen

namespace rotgen::python {

namespace py = pybind11;

// Hidden, as pybind11's own types are (the module is built with default visibility).
#define ROTGEN_PYTHON_LOCAL __attribute__((visibility("hidden")))

// The GIL released, symbolic_mutex() held, and `text` (when not empty) registered as the content of
// `path` (support/memory_files.hpp) for as long as the scope lives.
class ROTGEN_PYTHON_LOCAL symbolic_scope {
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

// Runs work() on a thread of its own with the GIL released. The calling thread waits, taking the
// GIL back every 5 ms to run the Python signal handlers (PyErr_CheckSignals: Ctrl-C); when one
// raises, `stop` is set, work() is expected to end soon after (at its next sample or member), and
// the handler's exception (KeyboardInterrupt) is raised here once it has. An exception work()
// throws is rethrown here, with the GIL held. No signal handler of the module's own is installed.
void run_released(const std::function<void()>& work, std::atomic<bool>& stop);

// The tests' hook (tests/python/module/test_threads.py): with ROTGEN_TEST_INTERLEAVE=1 in the
// environment, a simulate or sweep that has read its scene (and model) waits here, the GIL
// released, until another call has read its own after it (at most 2 s), so that the runs of two
// threads alternate: each integrates after the other thread has read another model. Without the
// variable it returns at once.
void interleave_test_hook();

// `scene` with method auto resolved (tune/: tuned, or read from the cache) with the GIL released
// and without symbolic_mutex(), which the tuning runs take as they need it; `text` (when not empty)
// registered as the content of `path` meanwhile (the cache key reads it); `use`: what the choice
// is for (tune.hpp: a sweep's takes no fixed steps, a lane sweep's only a method lanes run).
// simulate.cpp.
void resolve_released(scene_spec& scene, const std::string& path, const std::string& text,
                      auto_use use);

void init_errors(py::module_& m);
void init_model(py::module_& m);
void init_simulate(py::module_& m);
void init_sweep(py::module_& m);
void init_fit(py::module_& m);

} // namespace rotgen::python
