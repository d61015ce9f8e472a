// Command-line usage errors of `rotgen`, `rotgen inspect` and `rotgen emit` (generator/cli/):
// exit status 2, exactly one line on stderr naming the command (usage errors have no file) or
// the file, nothing on stdout and no output left behind. The messages are pinned as they are.
#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <tuple>

using namespace rotgen::test;
namespace fs = std::filesystem;

namespace {

void check_usage_error(const run_result& r, const std::string& line) {
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err == "rotgen: error: " + line + "\n");
}

} // namespace

TEST_CASE("cli: bad command lines of inspect give one line and exit 2", "[cli][errors]") {
    const std::string model = model_path("heavy_top");
    using row = std::tuple<std::string, std::string>;
    // arguments after `rotgen inspect`, the whole message line
    const auto [args, line] = GENERATE_COPY(table<std::string, std::string>({
        row{"'" + model + "' --format", "rotgen inspect: --format needs a value (text|latex|json)"},
        row{"'" + model + "' --format xml",
            "rotgen inspect: unknown format 'xml' (expected text, latex or json)"},
        row{"'" + model + "' --verbose", "rotgen inspect: unknown option '--verbose' for inspect"},
        row{"'" + model + "' other.yaml",
            "rotgen inspect: inspect takes one model or scene file, got '" + model +
                "' and 'other.yaml'"},
        row{"", "rotgen inspect: inspect needs a model or scene file: rotgen inspect "
                "MODEL.yaml|SCENE.yaml [--format text|latex|json] [--inertia [--symbolic]]"},
    }));
    INFO(args);
    check_usage_error(run_rotgen("inspect " + args), line);
}

TEST_CASE("cli: bad command lines of emit give one line, exit 2 and write nothing",
          "[cli][errors]") {
    const std::string model = model_path("heavy_top");
    const fs::path out = fs::path(ROTGEN_BINARY_DIR) / "cli_errors_emit_out";
    fs::remove_all(out);
    const std::string o = " -o '" + out.string() + "'";
    using row = std::tuple<std::string, std::string>;
    // arguments after `rotgen emit MODEL`, the whole message line
    const auto [args, line] = GENERATE_COPY(table<std::string, std::string>({
        row{o + " -o other", "rotgen emit: -o given twice"},
        row{o + " --form body --form body", "rotgen emit: --form given twice"},
        row{o + " --form",
            "rotgen emit: --form needs a value (lagrangian|hamiltonian|reduced|body|rotor)"},
        row{o + " --strategy solve --strategy solve", "rotgen emit: --strategy given twice"},
        row{o + " --outputs rhs --outputs rhs", "rotgen emit: --outputs given twice"},
        row{o + " --outputs rhs,,jacobian",
            "rotgen emit: --outputs: empty name in 'rhs,,jacobian'"},
        row{o + " --name a --name b", "rotgen emit: --name given twice"},
        row{o + " --frm body",
            "rotgen emit: unknown option '--frm' for emit; did you mean '--form'?"},
        row{o + " other.yaml",
            "rotgen emit: emit takes one model file, got '" + model + "' and 'other.yaml'"},
        row{"", "rotgen emit: emit needs an output directory: -o DIR"},
    }));
    INFO(args);
    check_usage_error(run_rotgen("emit '" + model + "'" + args), line);
    CHECK(!fs::exists(out));
}

TEST_CASE("cli: emit into a path that is a file names it and leaves it alone", "[cli][errors]") {
    const scratch_file file("cli_errors_not_a_dir", "keep\n");
    check_usage_error(run_rotgen("emit '" + model_path("heavy_top") + "' -o '" + file.path + "'"),
                      file.path + ": the output path exists and is not a directory");
    CHECK(read_file(file.path) == "keep\n");
}

TEST_CASE("cli: an unknown command gives one line and exit 2", "[cli][errors]") {
    check_usage_error(run_rotgen("frobnicate"),
                      "unknown command 'frobnicate' (expected inspect, emit, simulate, "
                      "bench, sweep, view, tune or fit; see rotgen --help)");
}
