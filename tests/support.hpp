// Shared helpers for the generator's tests.
#pragma once

#include "derive/derive.hpp"
#include "expr/symbols.hpp"
#include "spec/spec.hpp"

#include <ginac/ginac.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace rotgen::test {

inline std::string model_path(const std::string& name) {
    return std::string(ROTGEN_SOURCE_DIR) + "/models/" + name + ".yaml";
}

// A random point: angles with theta away from the singularity, rates, accelerations, momenta, t.
struct point {
    GiNaC::exmap values;
    explicit point(std::mt19937& rng, double theta_min = 0.3) {
        const auto& s = symbols();
        std::uniform_real_distribution<double> angle(0, 6.283185307179586);
        std::uniform_real_distribution<double> polar(theta_min, 3.141592653589793 - theta_min);
        std::uniform_real_distribution<double> rate(-2, 2);
        values[s.q[0]] = angle(rng);
        values[s.q[1]] = polar(rng);
        values[s.q[2]] = angle(rng);
        for (int i = 0; i < 3; ++i) {
            values[s.qd[i]] = rate(rng);
            values[s.qdd[i]] = rate(rng);
            values[s.p[i]] = rate(rng);
        }
        values[s.t] = rate(rng);
    }
};

// Evaluates e numerically with `at` and the model's parameter defaults.
inline double eval(const GiNaC::ex& e, const GiNaC::exmap& at, const model_spec& spec) {
    GiNaC::exmap all = spec.parameter_defaults();
    for (const auto& kv : at)
        all[kv.first] = kv.second;
    const GiNaC::ex v = GiNaC::evalf(e.subs(all));
    if (!GiNaC::is_a<GiNaC::numeric>(v)) throw std::runtime_error("not numeric after substitution");
    return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

// The result of running the rotgen executable.
struct run_result {
    int status = -1;
    std::string out, err;
};

inline std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Two headers `rotgen emit` wrote by the same command into two folders: `second` with its folder
// (which the regenerate command names) spelt as the first's, so that the two are meant to be equal.
struct emitted_pair {
    std::string name, first, second;
};

// The pairs of every header in folder `a` and its twin in folder `b`, in `a`'s listing order.
inline std::vector<emitted_pair> emitted_pairs(const std::string& a, const std::string& b) {
    std::vector<emitted_pair> pairs;
    for (const auto& entry : std::filesystem::directory_iterator(a)) {
        const std::string name = entry.path().filename().string();
        std::string second = read_file(b + "/" + name);
        const std::size_t at = second.find(b);
        if (at != std::string::npos) second.replace(at, b.size(), a);
        pairs.push_back({name, read_file(entry.path().string()), second});
    }
    return pairs;
}

// The lines of a text (without their line ends).
inline std::vector<std::string> text_lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
        out.push_back(line);
    return out;
}

// Runs `rotgen ARGS` (ARGS already shell-quoted) in `dir` (if not empty).
inline run_result run_rotgen(const std::string& args, const std::string& dir = "") {
    static int counter = 0;
    const std::string base = std::string(ROTGEN_BINARY_DIR) + "/tests_tmp_run" +
                             std::to_string(::getpid()) + "_" + std::to_string(counter++);
    const std::string cmd = (dir.empty() ? "" : "cd '" + dir + "' && ") + "'" + ROTGEN_EXE + "' " +
                            args + " >'" + base + ".out' 2>'" + base + ".err' </dev/null";
    const int raw = std::system(cmd.c_str());
    run_result r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = read_file(base + ".out");
    r.err = read_file(base + ".err");
    std::remove((base + ".out").c_str());
    std::remove((base + ".err").c_str());
    return r;
}

// A CSV's text without its provenance line (run/provenance.hpp: "# rotgen VERSION model ..."),
// which must be there: the text from the header on.
inline std::string without_provenance(const std::string& text) {
    if (text.rfind("# rotgen ", 0) != 0) return "(no provenance line) " + text;
    return text.substr(text.find('\n') + 1);
}

// A CSV of numbers with a header line, as `rotgen simulate` writes it (after its provenance line).
struct csv_table {
    std::vector<std::string> header;
    std::vector<std::vector<double>> rows;
    std::size_t column(const std::string& name) const {
        for (std::size_t i = 0; i < header.size(); ++i)
            if (header[i] == name) return i;
        throw std::runtime_error("no column " + name);
    }
    std::vector<double> values(const std::string& name) const {
        std::vector<double> v;
        for (const auto& r : rows)
            v.push_back(r.at(column(name)));
        return v;
    }
};

// Lines starting with '#' before the header (the provenance line, run/provenance.hpp) are skipped.
inline csv_table read_csv(const std::string& path) {
    csv_table t;
    std::istringstream in(read_file(path));
    std::string line, cell;
    while (std::getline(in, line) && !line.empty() && line[0] == '#') {
    }
    std::istringstream h(line);
    while (std::getline(h, cell, ','))
        t.header.push_back(cell);
    while (std::getline(in, line)) {
        std::istringstream r(line);
        std::vector<double> row;
        // strtod, not stod: stod throws on a subnormal value (ERANGE), strtod returns it
        while (std::getline(r, cell, ','))
            row.push_back(std::strtod(cell.c_str(), nullptr));
        t.rows.push_back(row);
    }
    return t;
}

// A scratch file holding `text`, removed at scope exit.
struct scratch_file {
    std::string path;
    scratch_file(const std::string& name, const std::string& text)
        : path(std::string(ROTGEN_BINARY_DIR) + "/" + name) {
        std::ofstream(path, std::ios::binary) << text;
    }
    ~scratch_file() { std::remove(path.c_str()); }
};

} // namespace rotgen::test
