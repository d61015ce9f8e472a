// rotgen fuzzing — what every target checks (the bad-input contract, DESIGN.md "Bad input"):
// any input gives a result or a rotgen::user_error; never a crash, an abort, a hang, another
// exception type, or a non-finite value in a result.
// A violation aborts with "rotgen-fuzz: CONTRACT VIOLATION: ..." so libFuzzer keeps the input.
#pragma once

#include "expr/symbols.hpp"
#include "spec/spec.hpp"
#include "support/error.hpp"

#include <Eigen/Eigenvalues>
#include <ginac/ginac.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <typeinfo>
#include <vector>

#include <unistd.h>

namespace rotgen::fuzz {

[[noreturn]] inline void violation(const std::string& what) {
    std::fprintf(stderr, "rotgen-fuzz: CONTRACT VIOLATION: %s\n", what.c_str());
    std::fflush(stderr);
    std::abort();
}

// A user error has a message. The CLI prints it on one line, escaping control characters that
// quoted user text (a YAML key with a newline, yaml-cpp's message about a NUL) brings in;
// ROTGEN_FUZZ_ONE_LINE=1 also requires the message itself to be one printable line.
inline void check_user_error(const user_error& e) {
    if (std::string(e.what()).empty()) violation("empty user_error message");
    static const bool one_line = [] {
        const char* v = std::getenv("ROTGEN_FUZZ_ONE_LINE");
        return v && std::string(v) == "1";
    }();
    if (!one_line) return;
    const std::string m = e.message();
    for (unsigned char c : m)
        if (c < 0x20 || c == 0x7f) violation("user_error message is not one printable line: " + m);
}

// Runs f(); a user_error is checked and accepted, anything else escaping is a violation.
template <class F> void expect_result_or_user_error(F&& f) {
    try {
        f();
    } catch (const user_error& e) {
        check_user_error(e);
    } catch (const std::exception& e) {
        violation(std::string("exception other than user_error escaped: ") + typeid(e).name() +
                  ": " + e.what());
    } catch (...) {
        violation("non-std exception escaped");
    }
}

// A scratch directory for the targets that read files (one per process; libFuzzer is
// single-threaded), removed at exit. Prefers /dev/shm (no disk writes per execution).
inline const std::string& scratch_dir() {
    static const std::string dir = [] {
        const char* base = std::getenv("ROTGEN_FUZZ_TMP");
        std::string tmpl =
            std::string(base ? base : (access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp")) +
            "/rotgen_fuzz_XXXXXX";
        if (!mkdtemp(tmpl.data())) {
            std::perror("rotgen-fuzz: mkdtemp");
            std::abort();
        }
        // Removed by an exit handler that does not touch `dir` (destroyed before it runs).
        static char cleanup[4096];
        std::snprintf(cleanup, sizeof cleanup, "%s", tmpl.c_str());
        std::atexit([] {
            std::error_code ignored;
            std::filesystem::remove_all(cleanup, ignored);
        });
        return tmpl;
    }();
    return dir;
}

inline void write_file(const std::string& path, const void* data, std::size_t size) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) {
        std::perror(("rotgen-fuzz: cannot write " + path).c_str());
        std::abort();
    }
}

inline std::string read_whole(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The value of e at `at` in double precision, as the generated kernels compute it (NaN if it is
// not real). Not GiNaC's evalf: that works in arbitrary precision and can run for minutes.
inline double double_value(const GiNaC::ex& e, const GiNaC::exmap& at) {
    using namespace GiNaC;
    if (is_a<numeric>(e)) return ex_to<numeric>(e).is_real() ? ex_to<numeric>(e).to_double() : NAN;
    if (is_a<symbol>(e)) {
        const auto it = at.find(e);
        return it == at.end() ? NAN : double_value(it->second, at);
    }
    if (is_a<constant>(e)) return ex_to<numeric>(evalf(e)).to_double();
    std::vector<double> v;
    for (std::size_t i = 0; i < e.nops(); ++i)
        v.push_back(double_value(e.op(i), at));
    if (is_a<add>(e)) {
        double r = 0;
        for (double x : v)
            r += x;
        return r;
    }
    if (is_a<mul>(e)) {
        double r = 1;
        for (double x : v)
            r *= x;
        return r;
    }
    if (is_a<power>(e)) return std::pow(v[0], v[1]);
    if (is_a<function>(e)) {
        const std::string f = ex_to<function>(e).get_name();
        static const std::map<std::string, double (*)(double)> unary{
            {"sin", std::sin},   {"cos", std::cos},   {"tan", std::tan},   {"asin", std::asin},
            {"acos", std::acos}, {"atan", std::atan}, {"sinh", std::sinh}, {"cosh", std::cosh},
            {"tanh", std::tanh}, {"exp", std::exp},   {"log", std::log},   {"abs", std::fabs}};
        if (v.size() == 1 && unary.count(f)) return unary.at(f)(v[0]);
        if (v.size() == 2 && f == "atan2") return std::atan2(v[0], v[1]);
    }
    const GiNaC::basic& node = GiNaC::ex_to<GiNaC::basic>(e);
    violation("an accepted expression holds something the double evaluator does not know: " +
              std::string(typeid(node).name()));
}

inline double finite_value(const GiNaC::ex& e, const GiNaC::exmap& at, const std::string& what) {
    const double d = double_value(e, at);
    if (std::isnan(d)) violation(what + " was accepted but is not a real number at the defaults");
    if (!std::isfinite(d)) violation(what + " was accepted but is not finite at the defaults");
    return d;
}

// The generic state spec.cpp checks expressions at (q = 0.3, 0.7, 1.1; q_dot = q / 2; t = 0.5).
inline GiNaC::exmap generic_state() {
    const auto& s = symbols();
    GiNaC::exmap m;
    const double values[3] = {0.3, 0.7, 1.1};
    for (int i = 0; i < 3; ++i) {
        m[s.q[i]] = values[i];
        m[s.qd[i]] = values[i] / 2;
    }
    m[s.t] = 0.5;
    return m;
}

// What load_model/parse_model promise about an accepted model, at the given parameter values.
inline void check_model(const model_spec& spec, const GiNaC::exmap& values) {
    for (const auto& p : spec.parameters)
        if (!std::isfinite(p.value))
            violation("parameter '" + p.name + "' has a non-finite default");
    GiNaC::exmap at = generic_state();
    for (const auto& kv : values)
        at[kv.first] = kv.second;
    Eigen::Matrix3d inertia;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            inertia(i, j) = finite_value(spec.inertia[i][j], at, "an inertia entry");
    if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() >
        1e-12 * inertia.cwiseAbs().maxCoeff())
        violation("an accepted inertia is not symmetric");
    const Eigen::Vector3d m = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
    if (!(m[0] > 0)) violation("an accepted inertia is not positive definite");
    finite_value(spec.potential, at, "the potential");
    for (int i = 0; i < 3; ++i) {
        finite_value(spec.damping[i], at, "a damping coefficient");
        finite_value(spec.torque[i], at, "a torque component");
    }
}

} // namespace rotgen::fuzz
