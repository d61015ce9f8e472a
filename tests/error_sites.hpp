// Shared checks of the tests/<stage>/test_<stage>_error_sites.cpp files (issue 13, item 5): a user
// error exits with status 2, prints exactly one line "rotgen: error: WHERE: PROBLEM" on stderr,
// nothing on stdout, and leaves no output behind.
#pragma once

#include "support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

namespace rotgen::test {

// `r` is the user error whose whole stderr line is "rotgen: error: " + line.
inline void check_error_line(const run_result& r, const std::string& line) {
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err == "rotgen: error: " + line + "\n");
}

// A scratch directory under the build tree, removed at construction and at scope exit.
struct scratch_dir {
    std::filesystem::path path;
    explicit scratch_dir(const std::string& name)
        : path(std::string(ROTGEN_BINARY_DIR) + "/" + name) {
        std::filesystem::remove_all(path);
    }
    ~scratch_dir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
};

} // namespace rotgen::test
