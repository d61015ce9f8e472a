// Issue 46, item 7: "the kernel cache keys on the path's spelling". The same model read as
// `sat.yaml` and as `/abs/dir/sat.yaml` compiled twice: the generated headers differed only in
// the comment naming the file. The cache keys on the code without its comment lines, so an empty
// cache holds one library after both runs.
#include "files_support.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>

using namespace rotgen::test;
namespace fs = std::filesystem;

namespace {

std::size_t libraries_in(const std::string& dir) {
    std::size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir))
        n += e.path().extension() == ".so" ? 1 : 0;
    return n;
}

} // namespace

TEST_CASE("the same model by two spellings of its path compiles once", "[simulate][cache]") {
    const std::string dir = fresh_folder("cache_spelling");
    const std::string cache = fresh_folder("cache_spelling_cache");
    fs::copy_file(model_path("heavy_top"), dir + "/sat.yaml");
    const std::string rest = "initial: {theta: 0.5, psi_dot: 30, phi: 0, psi: 0, phi_dot: 0, "
                             "theta_dot: 0}\ntime: {end: 1, samples: 3}\nrecord: [theta]\n";
    std::ofstream(dir + "/relative.yaml") << "model: sat.yaml\n" << rest;
    std::ofstream(dir + "/absolute.yaml") << "model: " << dir << "/sat.yaml\n" << rest;
    ::setenv("ROTGEN_CACHE_DIR", cache.c_str(), 1);
    const run_result first = run_rotgen("simulate relative.yaml -o a.csv", dir);
    const run_result second = run_rotgen("simulate absolute.yaml -o b.csv", dir);
    ::unsetenv("ROTGEN_CACHE_DIR");
    REQUIRE(first.status == 0);
    REQUIRE(second.status == 0);
    CHECK(first.out.find("emitting and compiling the kernels") != std::string::npos);
    CHECK(second.out.find("emitting and loading the cached kernels") != std::string::npos);
    CHECK(libraries_in(cache) == 1);
    // and the same rows
    const auto a = text_lines(read_file(dir + "/a.csv")), b = text_lines(read_file(dir + "/b.csv"));
    CHECK(a == b);
}
