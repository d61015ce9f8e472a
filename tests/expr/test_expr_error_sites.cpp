// The expression parser's user-error sites (generator/expr/expr_parse.cpp) that no other test
// reaches, one table row each: `rotgen emit` of a model whose potential is the bad expression
// exits 2 with one line naming the file, line and column, and writes no output directory.
#include "error_sites.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <tuple>

using namespace rotgen::test;

namespace {
const std::string top = "name: top\nparameters: {I1: 1.0, I3: 0.5}\ninertia: [I1, I1, I3]\n";
}

TEST_CASE("expr: each parser error site gives one line with line and column, exit 2, no output",
          "[expr][errors]") {
    using row = std::tuple<std::string, std::string, std::string>;
    // the potential as written after "potential: " on line 4, "LINE:COL", the problem
    const auto [potential, place, problem] = GENERATE(table<std::string, std::string, std::string>({
        row{"\"  \"", "4:15", "empty expression in potential"},
        row{"\"\"", "4:13", "empty expression in potential"},
        row{"theta)", "4:17", "unexpected ')' (expected an operator or the end) in potential"},
        row{"(theta theta)", "4:19", "expected ')' but found 'theta' in potential"},
        row{"tan(pi/2)", "4:12", "cannot evaluate: tan_eval(): simple pole in potential"},
        row{"(7^1000)^18*(7^1000)^18*(7^1000)^18", "4:35",
            "numbers too large (an exact value would have more than 39321 digits) in "
            "potential"},
        row{"(2^1000)^200", "4:20",
            "numbers too large (an exact value would have more than 39321 digits) in "
            "potential"},
        row{"theta/1000001^1000 + theta/1000002^1000 + theta/1000003^1000 + "
            "theta/1000004^1000",
            "4:12",
            "numbers too large (an exact value would have more than 39321 digits) in "
            "potential"},
        row{"0^(-1)", "4:13", "division by zero (0 raised to a non-positive power) in potential"},
        row{"theta^1001", "4:17",
            "exponent out of range (its magnitude must be at most 1000) in potential"},
        row{"(theta^1000)^2", "4:24",
            "exponent out of range (its magnitude must be at most 1000) in potential"},
        row{"1e99999999999999999999", "4:12", "bad number '1e99999999999999999999' in potential"},
        row{"1e5000", "4:12", "number out of range '1e5000' in potential"},
        row{"log(0)", "4:12", "log(0) is undefined in potential"},
        row{"\"*theta\"", "4:13", "unexpected '*' in potential"},
        row{"atan2(theta, theta, theta)", "4:12",
            "function 'atan2' takes 2 arguments, got 3 in potential"},
    }));
    INFO(potential);
    const scratch_file file("expr_error_site.yaml", top + "potential: " + potential + "\n");
    const scratch_dir out("expr_error_site_out");
    const run_result r =
        run_rotgen("emit expr_error_site.yaml -o '" + out.path.string() + "'", ROTGEN_BINARY_DIR);
    check_error_line(r, "expr_error_site.yaml:" + place + ": " + problem);
    CHECK(!std::filesystem::exists(out.path));
}
