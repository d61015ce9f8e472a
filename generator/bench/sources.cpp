// rotgen bench: finding the harness and the runtime headers.
#include "bench/sources.hpp"

#include "support/error.hpp"

#include <cstdlib>
#include <string>
#include <system_error>
#include <vector>

namespace rotgen::bench {

namespace fs = std::filesystem;

namespace {
bool complete(const bench_sources& c) {
    std::error_code ec;
    return fs::exists(c.harness / "harness.hpp", ec) && fs::exists(c.runtime / "rotgen.hpp", ec);
}
} // namespace

bench_sources first_complete(const std::vector<bench_sources>& candidates) {
    std::string looked;
    for (const auto& c : candidates) {
        if (complete(c)) return c;
        looked += (looked.empty() ? "" : ", ") + c.harness.string();
    }
    throw user_error({"rotgen bench"}, "cannot find the harness (bench/workprecision/harness.hpp) "
                                       "and the runtime headers; looked in " +
                                           looked +
                                           "; set ROTGEN_SOURCE_DIR to the rotgen source tree");
}

bench_sources find_bench_sources() {
    if (const char* d = std::getenv("ROTGEN_SOURCE_DIR"); d && *d) {
        // asked for explicitly: that tree or an error, never a silent fallback
        const bench_sources c{fs::path(d) / "bench/workprecision", fs::path(d) / "runtime"};
        if (!complete(c))
            throw user_error({"ROTGEN_SOURCE_DIR=" + std::string(d)},
                             "not a rotgen source tree (no bench/workprecision/harness.hpp and "
                             "runtime/rotgen.hpp there)");
        return c;
    }
    std::vector<bench_sources> candidates;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path prefix = exe.parent_path().parent_path();
        candidates.push_back(
            {prefix / "share/rotgen/bench/workprecision", prefix / "include/rotgen/runtime"});
    }
    const fs::path tree = ROTGEN_SOURCE_TREE; // set by generator/CMakeLists.txt
    candidates.push_back({tree / "bench/workprecision", tree / "runtime"});
    return first_complete(candidates);
}

} // namespace rotgen::bench
