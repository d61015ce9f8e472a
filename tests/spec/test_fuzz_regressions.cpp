// Inputs that crashed, hung or slipped through the parsers — found by the fuzz targets (fuzz/,
// kept in fuzz/regressions/TARGET/) or written for the hostile cases the fuzzer cannot reach in
// a few kilobytes (deep nesting, huge numbers, files over 1 MiB). Each must now give one user error
// line and exit status 2 (model and scene files, through the CLI), or a result or a user error
// (expressions, in process) — never a crash, an abort, a hang or another exception. Every case
// names its expected outcome: the error message (with its place), or the value parsed; a kept
// input without an expected outcome in the tables below fails the test.
#include "expr/angles.hpp"
#include "expr/expr_parse.hpp"
#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
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
            t[rotgen::angle_convention{}.names[i]] = s.q[i];
            t[rotgen::angle_convention{}.names[i] + "_dot"] = s.qd[i];
        }
        t["t"] = s.t;
        for (const char* p : {"I1", "I2", "I3", "M", "g", "h", "a", "b", "c", "w"})
            t[p] = GiNaC::realsymbol(p);
        return t;
    }();
    return table;
}

GiNaC::ex parse_fuzz(const std::string& text) {
    return rotgen::parse_expression(text, fuzz_names(), {"fuzz.yaml", 3, 12}, "torque");
}

// A user_error whose one-line message is `message` exactly ("fuzz.yaml:3:COL: problem"); any
// other exception, or a result, fails the test.
void expect_user_error(const std::string& text, const std::string& message) {
    try {
        (void)parse_fuzz(text);
        FAIL("parsed, expected the error " << message);
    } catch (const rotgen::user_error& e) {
        CHECK(e.message() == message);
        CHECK(printable_line(e.message()));
    }
}

// The expressions fuzz/regressions/expr/ keeps, with the error each must give.
const std::map<std::string, std::string>& kept_expression_errors() {
    const std::string range =
        "exponent out of range (its magnitude must be at most 1000) in torque";
    static const std::map<std::string, std::string> m{
        {"slow_long_number_to_huge_power", "fuzz.yaml:3:86: " + range},
        {"timeout_decimal_base_huge_exponent", "fuzz.yaml:3:47: " + range},
        {"timeout_decimal_to_huge_negative_power", "fuzz.yaml:3:22: " + range},
        {"timeout_huge_exponent_20_55555555550", "fuzz.yaml:3:16: " + range},
        {"timeout_huge_exponent_33_33333333333334", "fuzz.yaml:3:14: " + range},
        {"timeout_huge_exponent_5555", "fuzz.yaml:3:26: " + range},
        {"timeout_huge_negative_exponent_in_abs", "fuzz.yaml:3:25: " + range},
        {"timeout_power_tower_3_3_40", "fuzz.yaml:3:14: " + range},
        {"timeout_power_tower_555_55_5e308", "fuzz.yaml:3:19: " + range},
        {"timeout_power_tower_8_88_8", "fuzz.yaml:3:13: " + range},
    };
    return m;
}

// The model and scene files fuzz/regressions/ keeps, with the place and problem each must give.
const std::map<std::string, std::string>& kept_file_errors() {
    const std::string finite = " must be a finite number (0, or 2.2e-308 to 1.8e308 in magnitude)";
    static const std::map<std::string, std::string> m{
        {"subnormal_parameter_default.yaml", ":6:6: the default of parameter 'c'" + finite},
        {"subnormal_parameter_default_full_tensor_top.yaml",
         ":7:8: the default of parameter 'Izz'" + finite},
        {"subnormal_parameter_default_inline_model.yaml",
         ":3:19: the default of parameter 'A'" + finite},
        // a control byte: refused before yaml-cpp reads it (it used to quote it in its message)
        {"nul_in_yaml_error_message.yaml",
         ":1:2: not a text file (byte 0x03 here): a model or scene is YAML text"},
    };
    return m;
}

std::string expected_for(const std::map<std::string, std::string>& table, const fs::path& file) {
    const auto it = table.find(file.filename().string());
    if (it == table.end()) FAIL("no expected outcome for the kept input " << file.filename());
    return it == table.end() ? std::string() : it->second;
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
    CHECK(!problem.empty());
    CHECK(r.err.find(problem) != std::string::npos);
}

// A directory laid out like models/: DIR/*.yaml are the shipped models, scenes go in DIR/scenes/
// (so that `model: ../heavy_top.yaml` resolves, as in the fuzz target). One per test case: ctest
// runs the test cases in parallel.
fs::path scene_dir(const std::string& name) {
    const fs::path d = fs::path(ROTGEN_BINARY_DIR) / ("fuzz_regressions_" + name);
    fs::create_directories(d / "scenes");
    for (const auto& entry : fs::directory_iterator(fs::path(ROTGEN_SOURCE_DIR) / "models"))
        if (entry.is_regular_file() && entry.path().extension() == ".yaml")
            fs::copy_file(entry.path(), d / entry.path().filename(),
                          fs::copy_options::overwrite_existing);
    return d;
}

std::string repeat(const std::string& s, std::size_t n) {
    std::string r;
    r.reserve(s.size() * n);
    for (std::size_t i = 0; i < n; ++i)
        r += s;
    return r;
}

const std::string top = "name: top\nparameters: {I1: 1.0, I3: 0.5}\ninertia: [I1, I1, I3]\n";
const std::string start = "initial: {theta: 0.5, psi_dot: 30, phi: 0, psi: 0, phi_dot: 0, "
                          "theta_dot: 0}\ntime: {end: 1}\n";

} // namespace

TEST_CASE("fuzz regressions: kept expression inputs give their user error", "[fuzz][errors]") {
    const auto files = kept_inputs("expr");
    CHECK(files.size() == kept_expression_errors().size());
    for (const auto& file : files) {
        INFO(file.filename().string());
        expect_user_error(read_file(file.string()), expected_for(kept_expression_errors(), file));
    }
}

TEST_CASE("fuzz regressions: kept model inputs give their user error line", "[fuzz][errors]") {
    const auto files = kept_inputs("model");
    CHECK(files.size() == 2);
    for (const auto& file : files) {
        INFO(file.filename().string());
        check_one_user_error(run_limited("inspect '" + file.string() + "'"),
                             file.string() + expected_for(kept_file_errors(), file));
    }
}

TEST_CASE("fuzz regressions: kept scene inputs give their user error line", "[fuzz][errors]") {
    const fs::path dir = scene_dir("kept");
    const auto files = kept_inputs("scene");
    CHECK(files.size() == 1);
    for (const auto& file : files) {
        INFO(file.filename().string());
        const fs::path copy = dir / "scenes" / file.filename();
        fs::copy_file(file, copy, fs::copy_options::overwrite_existing);
        check_one_user_error(run_limited("simulate '" + copy.string() + "'"),
                             copy.string() + expected_for(kept_file_errors(), file));
    }
}

TEST_CASE("fuzz regressions: hostile expressions are bounded", "[fuzz][errors]") {
    // Each used to overflow the stack, run for minutes or exhaust the memory.
    const std::string nested = "expression nested too deeply (more than 200 levels) in torque";
    const std::string range =
        "exponent out of range (its magnitude must be at most 1000) in torque";
    expect_user_error(repeat("(", 100000) + "phi" + repeat(")", 100000),
                      "fuzz.yaml:3:212: " + nested);
    expect_user_error(repeat("sin(", 50000) + "phi" + repeat(")", 50000),
                      "fuzz.yaml:3:812: " + nested);
    expect_user_error(repeat("phi^", 50000) + "2", "fuzz.yaml:3:812: " + nested);
    expect_user_error("9^9^9^9", "fuzz.yaml:3:15: " + range);
    expect_user_error("pow(7, 99999999)", "fuzz.yaml:3:12: " + range);
    expect_user_error("2^(99999999/2)", "fuzz.yaml:3:13: " + range);
    expect_user_error("((phi + 1)^1000)^1000",
                      "fuzz.yaml:3:22: a sum raised to a power above 32 is not supported (the "
                      "derivation expands it) in torque");
    expect_user_error(repeat("1e4000*", 20000) + "1",
                      "fuzz.yaml:3:74: numbers too large (an exact value would have more than "
                      "39321 digits) in torque");
    expect_user_error(std::string(10000, '7'),
                      "fuzz.yaml:3:12: number with more than 4000 digits in torque");
    expect_user_error(std::string("phi\0", 4) + "+1",
                      "fuzz.yaml:3:15: unexpected character '\\x00' in torque");
    expect_user_error("sqrt(-1) + log(0) + pow(0, -1) + 0^0",
                      "fuzz.yaml:3:23: log(0) is undefined in torque");
    // Accepted: signs are not nesting; 200000 minus signs cancel.
    const auto& s = rotgen::symbols();
    CHECK((parse_fuzz(repeat("-", 200000) + "phi") - s.q[0]).is_zero());
    CHECK((parse_fuzz(repeat("-", 199999) + "phi") + s.q[0]).is_zero());
    // Long but harmless: a sum of 50000 distinct terms is linear, not quadratic, to parse.
    std::string sum = "0";
    GiNaC::ex expected = 0;
    for (int i = 1; i <= 50000; ++i) {
        sum += "+sin(" + std::to_string(i) + "*phi)";
        expected += GiNaC::sin(i * s.q[0]);
    }
    const GiNaC::ex parsed = parse_fuzz(sum);
    CHECK(parsed.nops() == 50000);
    CHECK((parsed - expected).is_zero());
}

TEST_CASE("fuzz regressions: hostile model files give one user error line", "[fuzz][errors]") {
    using row = std::tuple<std::string, std::string, std::string>;
    // name, file contents, expected text in the message
    const std::string bomb =
        "description: [&a [x, x, x, x, x, x, x, x, x], &b [*a, *a, *a, *a, *a, *a, *a, *a, *a], "
        "&c [*b, *b, *b, *b, *b, *b, *b, *b, *b], &d [*c, *c, *c, *c, *c, *c, *c, *c, *c], "
        "&e [*d, *d, *d, *d, *d, *d, *d, *d, *d], &f [*e, *e, *e, *e, *e, *e, *e, *e, *e], "
        "&g [*f, *f, *f, *f, *f, *f, *f, *f, *f], &h [*g, *g, *g, *g, *g, *g, *g, *g, *g]]\n";
    const auto [name, text, problem] = GENERATE_COPY(table<std::string, std::string, std::string>({
        row{"deep parentheses",
            top + "potential: " + repeat("(", 100000) + "theta" + repeat(")", 100000) + "\n",
            "nested too deeply"},
        row{"deep calls",
            top + "potential: " + repeat("cos(", 20000) + "theta" + repeat(")", 20000) + "\n",
            "nested too deeply"},
        row{"power tower", top + "potential: 9^9^9^9\n", "exponent out of range"},
        row{"huge exponent", top + "potential: theta^99999999\n", "exponent out of range"},
        row{"huge power of a number", top + "potential: pow(7, 99999999)\n",
            "exponent out of range"},
        row{"enormous product", top + "potential: " + repeat("1e4000*", 100) + "cos(theta)\n",
            "numbers too large"},
        row{"10000 digits", top + "potential: " + std::string(10000, '3') + "\n",
            "more than 4000 digits"},
        row{"1e4000 in the inertia", "name: top\ninertia: [1e4000, 1e4000, 1e4000]\n",
            "inertia is not a finite real number"},
        row{"sqrt(-1) in the inertia", "name: top\ninertia: [\"1 + sqrt(-1)\", 2, 2]\n",
            "inertia is not a finite real number"},
        row{"a subnormal default (GiNaC::numeric(double) threw CLN's underflow exception)",
            "name: top\nparameters: {a: 1e-310}\ninertia: [1, 1, 1]\n", "must be a finite number"},
        row{"sqrt(-1) in the potential", top + "potential: sqrt(-1)*cos(theta)\n",
            "not a finite real number"},
        row{"pow(0, -1)", top + "potential: pow(0, -1)\n", "division by zero"},
        row{"0^0", top + "potential: 0^0\n", "division by zero"},
        row{"log(0)", top + "potential: log(0)\n", "log(0) is undefined"},
        row{"sin(exp(exp(20))) took minutes in evalf", top + "potential: sin(exp(exp(22)))\n",
            "not a finite real number"},
        row{"gravity whose product overflows",
            top + "gravity: {mass: 1e300, g: 1e300, com: [0, 0, 1]}\n",
            "the potential with gravity is not a finite real number"},
        row{"a 300000-character name (std::regex overflowed the stack)",
            "name: " + std::string(300000, 'a') + "\ninertia: [1, 1, 1]\n",
            "must be a C++ identifier"},
        row{"a 300000-digit default (std::regex overflowed the stack)",
            "name: top\nparameters: {a: " + std::string(300000, '1') + "}\ninertia: [1, 1, 1]\n",
            "must be a finite number"},
        row{"a file over 1 MiB", top + "# " + std::string(1100000, 'x') + "\n",
            "file is larger than 1 MiB"},
        row{"billion laughs (aliases are shared, never expanded)", top + bomb + "damping: *h\n",
            "'damping' must be one coefficient, a list of three, or {body: [c1, c2, c3]}"},
        row{"deeply nested YAML",
            "name: top\ninertia: " + repeat("[", 100000) + repeat("]", 100000) + "\n",
            "fuzz_regression_model.yaml:2:200010: malformed YAML: bad file"},
    }));
    INFO(name);
    const scratch_file file("fuzz_regression_model.yaml", text);
    check_one_user_error(run_limited("inspect '" + file.path + "'"), problem);
}

TEST_CASE("fuzz regressions: hostile scene files give one user error line", "[fuzz][errors]") {
    using row = std::tuple<std::string, std::string, std::string>;
    const auto [name, text, problem] = GENERATE_COPY(table<std::string, std::string, std::string>({
        row{"model: /dev/zero used to read forever", "model: /dev/zero\n" + start,
            "file is larger than 1 MiB"},
        row{"an override that makes the inertia negative",
            "model: ../heavy_top.yaml\nparameters: {I3: -5}\n" + start,
            "with these parameter values the model"},
        row{"an override that puts 0 under a division",
            "model: {name: t, parameters: {a: 1}, inertia: [1, 1, 1], potential: 1/a*cos(theta)}\n"
            "parameters: {a: 0}\n" +
                start,
            "with these parameter values the model"},
        row{"a time span that overflows",
            "model: ../heavy_top.yaml\ninitial: {theta: 0.5, phi: 0, psi: 0, phi_dot: 0, "
            "theta_dot: 0, psi_dot: 0}\n"
            "time: {start: -1e308, end: 1e308}\n",
            "time span"},
        row{"max_steps below 1 (was cast to 0)",
            "model: ../heavy_top.yaml\n" + start + "integrator: {method: dop853, max_steps: 0.5}\n",
            "max_steps must be a whole number"},
        row{"max_steps 1e300 (undefined cast to long)",
            "model: ../heavy_top.yaml\n" + start +
                "integrator: {method: dop853, max_steps: 1e300}\n",
            "max_steps must be a whole number"},
        row{"a subnormal initial angle",
            "model: ../heavy_top.yaml\ninitial: {theta: 0.5, phi: 1e-310, psi: 0, phi_dot: 0, "
            "theta_dot: 0, psi_dot: 0}\ntime: {end: 1}\n",
            "must be 0 or at least 2.2e-308 in magnitude"},
        row{"a subnormal parameter override",
            "model: ../heavy_top.yaml\nparameters: {h: -1e-310}\n" + start,
            "must be 0 or at least 2.2e-308 in magnitude"},
        row{"a 400000-digit number (std::regex overflowed the stack)",
            "model: ../heavy_top.yaml\ninitial: {theta: " + std::string(400000, '1') +
                ", phi: 0, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\ntime: {end: 1}\n",
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
    const auto files = kept_inputs("model_one_line");
    CHECK(files.size() == 1);
    for (const auto& file : files) {
        INFO(file.filename().string());
        check_one_user_error(run_limited("inspect '" + file.string() + "'"),
                             file.string() + expected_for(kept_file_errors(), file));
    }
}

TEST_CASE("fuzz regressions: control characters in quoted names stay on one line",
          "[fuzz][errors]") {
    using row = std::tuple<std::string, std::string, std::string>;
    // name, file contents, the message after the file name: control characters escaped
    const auto [name, text, message] = GENERATE(table<std::string, std::string, std::string>({
        row{"a key with a newline", top + "\"foo\\nbar\": 1\n",
            ":4:2: unknown field 'foo\\nbar' in the model"},
        row{"a parameter name with a newline",
            "name: top\nparameters: {\"a\\nb\": 1}\ninertia: [1, 1, 1]\n",
            ":2:15: parameter name 'a\\nb' is not an identifier"},
        row{"a parameter name with a carriage return",
            "name: top\nparameters: {\"a\\rb\": 1}\ninertia: [1, 1, 1]\n",
            ":2:15: parameter name 'a\\x0db' is not an identifier"},
        row{"a NUL byte (refused as binary before yaml-cpp quotes it)",
            top + std::string("potential: cos(theta)\0\n", 23),
            ":4:22: not a text file (byte 0x00 here): a model or scene is YAML text"},
    }));
    INFO(name);
    const scratch_file file("fuzz_regression_control.yaml", text);
    check_one_user_error(run_limited("inspect '" + file.path + "'"), file.path + message);
}
