// Inputs that crashed, hung or slipped through the parsers — found by the fuzz targets (fuzz/,
// kept in fuzz/regressions/TARGET/) or written for the hostile cases the fuzzer cannot reach in
// a few kilobytes (deep nesting, huge numbers, files over 1 MiB). Each must now give one user error
// line and exit status 2 (model and scene files, through the CLI), or a result or a user error
// (expressions, in process) — never a crash, an abort, a hang or another exception.
#include "expr/expr_parse.hpp"
#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <tuple>
#include <vector>

using namespace rotgen::test;
namespace fs = std::filesystem;

namespace {

std::vector<fs::path> kept_inputs(const std::string& target) {
    std::vector<fs::path> files;
    const fs::path dir = fs::path(ROTGEN_SOURCE_DIR) / "fuzz" / "regressions" / target;
    if (fs::is_directory(dir))
        for (const auto& entry : fs::directory_iterator(dir))
            if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

bool printable_line(const std::string& s) {
    return std::none_of(s.begin(), s.end(), [](char c) {
        const auto u = static_cast<unsigned char>(c);
        return u < 0x20 || u == 0x7f;
    });
}

// The name table of fuzz/fuzz_expr.cpp: a torque's names and a few parameters.
const rotgen::name_table& fuzz_names() {
    static const rotgen::name_table table = [] {
        rotgen::name_table t;
        const auto& s = rotgen::symbols();
        for (int i = 0; i < 3; ++i) {
            t[rotgen::coordinate_names()[i]] = s.q[i];
            t[rotgen::coordinate_names()[i] + "_dot"] = s.qd[i];
        }
        t["t"] = s.t;
        for (const char* p : {"I1", "I2", "I3", "M", "g", "h", "a", "b", "c", "w"})
            t[p] = GiNaC::realsymbol(p);
        return t;
    }();
    return table;
}

// A result or a user_error with a one-line message; any other exception fails the test.
void parse_or_user_error(const std::string& text) {
    try {
        (void)rotgen::parse_expression(text, fuzz_names(), {"fuzz.yaml", 3, 12}, "torque");
    } catch (const rotgen::user_error& e) {
        INFO(e.message());
        CHECK(printable_line(e.message()));
    }
}

// `rotgen ARGS` with a time limit (exit status 124 if it is reached).
run_result run_limited(const std::string& args) {
    static int counter = 0;
    const std::string base = std::string(ROTGEN_BINARY_DIR) + "/tests_tmp_fuzz" +
                             std::to_string(::getpid()) + "_" + std::to_string(counter++);
    const std::string cmd = "timeout 120 '" + std::string(ROTGEN_EXE) + "' " + args + " >'" + base +
                            ".out' 2>'" + base + ".err' </dev/null";
    const int raw = std::system(cmd.c_str());
    run_result r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = read_file(base + ".out");
    r.err = read_file(base + ".err");
    std::remove((base + ".out").c_str());
    std::remove((base + ".err").c_str());
    return r;
}

void check_one_user_error(const run_result& r, const std::string& problem) {
    INFO(r.err.substr(0, 2000));
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("rotgen: error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(printable_line(r.err.substr(0, r.err.size() - 1)));
    if (!problem.empty()) CHECK(r.err.find(problem) != std::string::npos);
}

// A directory laid out like models/: DIR/*.yaml are the shipped models, scenes go in DIR/scenes/
// (so that `model: ../heavy_top.yaml` resolves, as in the fuzz target). One per test case: ctest
// runs the test cases in parallel.
fs::path scene_dir(const std::string& name) {
    const fs::path d = fs::path(ROTGEN_BINARY_DIR) / ("fuzz_regressions_" + name);
    fs::create_directories(d / "scenes");
    for (const auto& entry : fs::directory_iterator(fs::path(ROTGEN_SOURCE_DIR) / "models"))
        if (entry.is_regular_file() && entry.path().extension() == ".yaml")
            fs::copy_file(entry.path(), d / entry.path().filename(), fs::copy_options::overwrite_existing);
    return d;
}

std::string repeat(const std::string& s, std::size_t n) {
    std::string r;
    r.reserve(s.size() * n);
    for (std::size_t i = 0; i < n; ++i) r += s;
    return r;
}

const std::string top = "name: top\nparameters: {I1: 1.0, I3: 0.5}\ninertia: [I1, I1, I3]\n";
const std::string start = "initial: {theta: 0.5, psi_dot: 30}\ntime: {end: 1}\n";

} // namespace

TEST_CASE("fuzz regressions: kept expression inputs parse or give a user error", "[fuzz][errors]") {
    for (const auto& file : kept_inputs("expr")) {
        INFO(file.filename().string());
        parse_or_user_error(read_file(file.string()));
    }
}

TEST_CASE("fuzz regressions: kept model inputs give one user error line", "[fuzz][errors]") {
    for (const auto& file : kept_inputs("model")) {
        INFO(file.filename().string());
        check_one_user_error(run_limited("inspect '" + file.string() + "'"), "");
    }
}

TEST_CASE("fuzz regressions: kept scene inputs give one user error line", "[fuzz][errors]") {
    const fs::path dir = scene_dir("kept");
    for (const auto& file : kept_inputs("scene")) {
        INFO(file.filename().string());
        const fs::path copy = dir / "scenes" / file.filename();
        fs::copy_file(file, copy, fs::copy_options::overwrite_existing);
        check_one_user_error(run_limited("simulate '" + copy.string() + "'"), "");
    }
}

TEST_CASE("fuzz regressions: hostile expressions are bounded", "[fuzz][errors]") {
    // Each used to overflow the stack, run for minutes or exhaust the memory.
    parse_or_user_error(repeat("(", 100000) + "phi" + repeat(")", 100000));
    parse_or_user_error(repeat("sin(", 50000) + "phi" + repeat(")", 50000));
    parse_or_user_error(repeat("phi^", 50000) + "2");
    parse_or_user_error(repeat("-", 200000) + "phi"); // accepted: signs are not nesting
    parse_or_user_error("9^9^9^9");
    parse_or_user_error("pow(7, 99999999)");
    parse_or_user_error("2^(99999999/2)");
    parse_or_user_error("((phi + 1)^1000)^1000");
    parse_or_user_error(repeat("1e4000*", 20000) + "1");
    parse_or_user_error(std::string(10000, '7'));
    parse_or_user_error(std::string("phi\0", 4) + "+1");
    parse_or_user_error("sqrt(-1) + log(0) + pow(0, -1) + 0^0");
    // Long but harmless: a sum of 50000 distinct terms is linear, not quadratic, to parse.
    std::string sum = "0";
    for (int i = 1; i <= 50000; ++i) sum += "+sin(" + std::to_string(i) + "*phi)";
    parse_or_user_error(sum);
}

TEST_CASE("fuzz regressions: hostile model files give one user error line", "[fuzz][errors]") {
    using row = std::tuple<std::string, std::string, std::string>;
    // name, file contents, expected text in the message
    const std::string bomb = "description: [&a [x, x, x, x, x, x, x, x, x], &b [*a, *a, *a, *a, *a, *a, *a, *a, *a], "
                             "&c [*b, *b, *b, *b, *b, *b, *b, *b, *b], &d [*c, *c, *c, *c, *c, *c, *c, *c, *c], "
                             "&e [*d, *d, *d, *d, *d, *d, *d, *d, *d], &f [*e, *e, *e, *e, *e, *e, *e, *e, *e], "
                             "&g [*f, *f, *f, *f, *f, *f, *f, *f, *f], &h [*g, *g, *g, *g, *g, *g, *g, *g, *g]]\n";
    const auto [name, text, problem] = GENERATE_COPY(table<std::string, std::string, std::string>({
        row{"deep parentheses", top + "potential: " + repeat("(", 100000) + "theta" + repeat(")", 100000) + "\n",
            "nested too deeply"},
        row{"deep calls", top + "potential: " + repeat("cos(", 20000) + "theta" + repeat(")", 20000) + "\n",
            "nested too deeply"},
        row{"power tower", top + "potential: 9^9^9^9\n", "exponent out of range"},
        row{"huge exponent", top + "potential: theta^99999999\n", "exponent out of range"},
        row{"huge power of a number", top + "potential: pow(7, 99999999)\n", "exponent out of range"},
        row{"enormous product", top + "potential: " + repeat("1e4000*", 100) + "cos(theta)\n",
            "numbers too large"},
        row{"10000 digits", top + "potential: " + std::string(10000, '3') + "\n", "more than 4000 digits"},
        row{"1e4000 in the inertia", "name: top\ninertia: [1e4000, 1e4000, 1e4000]\n",
            "inertia is not a finite real number"},
        row{"sqrt(-1) in the inertia", "name: top\ninertia: [\"1 + sqrt(-1)\", 2, 2]\n",
            "inertia is not a finite real number"},
        row{"a subnormal default (GiNaC::numeric(double) threw CLN's underflow exception)",
            "name: top\nparameters: {a: 1e-310}\ninertia: [1, 1, 1]\n", "must be a finite number"},
        row{"sqrt(-1) in the potential", top + "potential: sqrt(-1)*cos(theta)\n", "not a finite real number"},
        row{"pow(0, -1)", top + "potential: pow(0, -1)\n", "division by zero"},
        row{"0^0", top + "potential: 0^0\n", "division by zero"},
        row{"log(0)", top + "potential: log(0)\n", "log(0) is undefined"},
        row{"sin(exp(exp(20))) took minutes in evalf", top + "potential: sin(exp(exp(22)))\n",
            "not a finite real number"},
        row{"gravity whose product overflows", top + "gravity: {mass: 1e300, g: 1e300, com: [0, 0, 1]}\n",
            "the potential with gravity is not a finite real number"},
        row{"a 300000-character name (std::regex overflowed the stack)",
            "name: " + std::string(300000, 'a') + "\ninertia: [1, 1, 1]\n", "must be a C++ identifier"},
        row{"a 300000-digit default (std::regex overflowed the stack)",
            "name: top\nparameters: {a: " + std::string(300000, '1') + "}\ninertia: [1, 1, 1]\n",
            "must be a finite number"},
        row{"a file over 1 MiB", top + "# " + std::string(1100000, 'x') + "\n", "file is larger than 1 MiB"},
        row{"billion laughs (aliases are shared, never expanded)", top + bomb + "damping: *h\n",
            "'damping' must be one coefficient or a list of three"},
        row{"deeply nested YAML", "name: top\ninertia: " + repeat("[", 100000) + repeat("]", 100000) + "\n", ""},
    }));
    INFO(name);
    const scratch_file file("fuzz_regression_model.yaml", text);
    check_one_user_error(run_limited("inspect '" + file.path + "'"), problem);
}

TEST_CASE("fuzz regressions: hostile scene files give one user error line", "[fuzz][errors]") {
    using row = std::tuple<std::string, std::string, std::string>;
    const auto [name, text, problem] = GENERATE_COPY(table<std::string, std::string, std::string>({
        row{"model: /dev/zero used to read forever", "model: /dev/zero\n" + start, "file is larger than 1 MiB"},
        row{"an override that makes the inertia negative",
            "model: ../heavy_top.yaml\nparameters: {I3: -5}\n" + start,
            "with these parameter values the model"},
        row{"an override that puts 0 under a division",
            "model: {name: t, parameters: {a: 1}, inertia: [1, 1, 1], potential: 1/a*cos(theta)}\n"
            "parameters: {a: 0}\n" + start,
            "with these parameter values the model"},
        row{"a time span that overflows", "model: ../heavy_top.yaml\ninitial: {theta: 0.5}\n"
                                          "time: {start: -1e308, end: 1e308}\n",
            "time span"},
        row{"max_steps below 1 (was cast to 0)",
            "model: ../heavy_top.yaml\n" + start + "integrator: {method: dop853, max_steps: 0.5}\n",
            "max_steps must be a whole number"},
        row{"max_steps 1e300 (undefined cast to long)",
            "model: ../heavy_top.yaml\n" + start + "integrator: {method: dop853, max_steps: 1e300}\n",
            "max_steps must be a whole number"},
        row{"a subnormal initial angle", "model: ../heavy_top.yaml\ninitial: {theta: 0.5, phi: 1e-310}\ntime: {end: 1}\n",
            "must be 0 or at least 2.2e-308 in magnitude"},
        row{"a subnormal parameter override", "model: ../heavy_top.yaml\nparameters: {h: -1e-310}\n" + start,
            "must be 0 or at least 2.2e-308 in magnitude"},
        row{"a 400000-digit number (std::regex overflowed the stack)",
            "model: ../heavy_top.yaml\ninitial: {theta: " + std::string(400000, '1') + "}\ntime: {end: 1}\n",
            "must be a finite number"},
    }));
    INFO(name);
    const fs::path path = scene_dir("hostile") / "scenes" / "fuzz_regression_scene.yaml";
    std::ofstream(path, std::ios::binary) << text;
    check_one_user_error(run_limited("simulate '" + path.string() + "'"), problem);
}

// Messages quote user text (a key, a parameter name, a path, yaml-cpp's message about a byte); a
// control character in it must not break the one-line format (the CLI escapes them). Kept fuzz
// inputs of this kind are in fuzz/regressions/model_one_line/ (the in-process fuzz target does not
// see the CLI's escaping, so run.sh does not replay them).
TEST_CASE("fuzz regressions: kept inputs with control characters in messages", "[fuzz][errors]") {
    for (const auto& file : kept_inputs("model_one_line")) {
        INFO(file.filename().string());
        check_one_user_error(run_limited("inspect '" + file.string() + "'"), "");
    }
}

TEST_CASE("fuzz regressions: control characters in quoted names stay on one line", "[fuzz][errors]") {
    using row = std::tuple<std::string, std::string>;
    const auto [name, text] = GENERATE(table<std::string, std::string>({
        row{"a key with a newline", top + "\"foo\\nbar\": 1\n"},
        row{"a parameter name with a newline", "name: top\nparameters: {\"a\\nb\": 1}\ninertia: [1, 1, 1]\n"},
        row{"a parameter name with a carriage return", "name: top\nparameters: {\"a\\rb\": 1}\ninertia: [1, 1, 1]\n"},
        row{"a NUL byte (yaml-cpp quotes it in its message)", top + std::string("potential: cos(theta)\0\n", 23)},
    }));
    INFO(name);
    const scratch_file file("fuzz_regression_control.yaml", text);
    check_one_user_error(run_limited("inspect '" + file.path + "'"), "");
}
