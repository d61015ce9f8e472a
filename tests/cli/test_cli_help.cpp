// Every command's --help: exit 0, a usage line, every option listed, and the lines of a
// several-line option help starting under its text (the column after the longest option).
#include "support.hpp"

#include <catch2/catch.hpp>

using namespace rotgen::test;

TEST_CASE("cli: every command's help lists its options in aligned columns", "[cli]") {
    const std::string command =
        GENERATE("inspect", "emit", "simulate", "bench", "sweep", "view", "tune", "fit");
    const run_result r = run_rotgen(command + " --help");
    INFO(command << ":\n" << r.out);
    REQUIRE(r.status == 0);
    const std::vector<std::string> lines = text_lines(r.out);
    REQUIRE(!lines.empty());
    CHECK(lines[0].rfind("usage: rotgen " + command + " ", 0) == 0);
    std::size_t column = 0, options = 0, continued = 0;
    bool in_options = false;
    for (const std::string& line : lines) {
        if (line == "options:") {
            in_options = true;
            continue;
        }
        if (!in_options || line.empty()) continue;
        if (line.rfind("  -", 0) == 0) { // an option: its text starts after two or more spaces
            ++options;
            const std::size_t gap = line.find("  ", 2);
            REQUIRE(gap != std::string::npos);
            const std::size_t text = line.find_first_not_of(' ', gap);
            if (column == 0) column = text;
            CHECK(text == column);
        } else { // a continuation line
            ++continued;
            CHECK(line.find_first_not_of(' ') == column);
        }
    }
    CHECK(options >= 2); // at least one of the command's own and --help
    if (command == "sweep" || command == "emit") CHECK(continued >= 1);
}
