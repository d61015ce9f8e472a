// User errors become rotgen.InputError (python/rotgen/_errors.py: a ValueError with file, line,
// column; str() the CLI's line without "rotgen: error: ").
#include "bindings.hpp"

#include "support/error.hpp"

namespace rotgen::python {

namespace {

// The CLI's one line (cli.cpp prints newlines and tabs escaped).
std::string one_line(const std::string& text) {
    std::string out;
    for (char c : text)
        out += c == '\n' ? std::string("\\n") : c == '\t' ? std::string("\\t") : std::string(1, c);
    return out;
}

void raise_input_error(const user_error& e) {
    const py::object cls = py::module_::import("rotgen._errors").attr("InputError");
    const source_location& w = e.where();
    const py::object line = w.line > 0 ? py::object(py::int_(w.line)) : py::object(py::none());
    const py::object column =
        w.column > 0 ? py::object(py::int_(w.column)) : py::object(py::none());
    const py::object error = cls(one_line(e.message()), w.file, line, column);
    PyErr_SetObject(cls.ptr(), error.ptr());
}

} // namespace

void init_errors(py::module_&) {
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const user_error& e) {
            raise_input_error(e);
        }
    });
}

} // namespace rotgen::python
