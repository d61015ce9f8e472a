// _rotgen: the compiled core of the `rotgen` Python package (python/rotgen/). One file per stage
// it exposes; each binding calls the library functions the commands in generator/cli/ call.
#include "bindings.hpp"

#include "run/prepared.hpp"
#include "support/memory_files.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <string>
#include <thread>

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

void run_released(const std::function<void()>& work, std::atomic<bool>& stop) {
    std::mutex m;
    std::condition_variable finished;
    bool done = false;
    std::exception_ptr failure;
    bool raised = false;
    {
        py::gil_scoped_release released;
        std::thread worker([&] {
            try {
                work();
            } catch (...) {
                failure = std::current_exception();
            }
            const std::lock_guard<std::mutex> lock(m);
            done = true;
            finished.notify_all();
        });
        std::unique_lock<std::mutex> lock(m);
        while (!finished.wait_for(lock, std::chrono::milliseconds(5), [&] { return done; })) {
            if (raised) continue;
            lock.unlock();
            {
                py::gil_scoped_acquire gil;
                raised = PyErr_CheckSignals() != 0; // the handler's exception is now set
            }
            if (raised) stop = true;
            lock.lock();
        }
        lock.unlock();
        worker.join();
    }
    if (raised) throw py::error_already_set();
    if (failure) std::rethrow_exception(failure);
}

void interleave_test_hook() {
    const char* on = std::getenv("ROTGEN_TEST_INTERLEAVE");
    if (!on || std::string(on) != "1") return;
    // The hook's own count of reads, guarded by its own lock m (a test hook: no run reads it, and
    // it holds no per-model or per-run fact).
    static std::mutex m;
    static std::condition_variable read; // waited on under m
    static std::uint64_t reads = 0;      // guarded by m
    py::gil_scoped_release released;
    std::unique_lock<std::mutex> lock(m);
    const std::uint64_t mine = ++reads;
    read.notify_all();
    read.wait_for(lock, std::chrono::seconds(2), [&] { return reads > mine; });
}

} // namespace rotgen::python

PYBIND11_MODULE(_rotgen, m) {
    m.doc() = "rotgen's compiled core: the run, sweep, inspect and emit stages (use `rotgen`)";
    m.attr("version") = ROTGEN_VERSION;
    rotgen::python::init_errors(m);
    rotgen::python::init_model(m);
    rotgen::python::init_simulate(m);
    rotgen::python::init_sweep(m);
    rotgen::python::init_fit(m);
}
