// `rotgen fit` on the command line: its outputs, its refusals (located, exit 2, nothing written)
// and a fit that does not converge (exit 3, the last iterate in the partial file).
#include "fit_support.hpp"

#include <catch2/catch.hpp>

#include <filesystem>

using namespace rotgen;
using namespace rotgen::test;
using Catch::Matchers::Contains;

namespace {

namespace fs = std::filesystem;

const std::string free_scene = std::string(ROTGEN_SOURCE_DIR) + "/tests/fit/free_body_fit.yaml";

// A folder of its own holding the free body's gyro data (truth I1 = 1, I2 = 2) as data.csv.
struct cli_folder {
    std::string dir;
    explicit cli_folder(const std::string& name)
        : dir(std::string(ROTGEN_BINARY_DIR) + "/tests_tmp_fit_" + name) {
        fs::remove_all(dir);
        fs::create_directories(dir);
        const synthetic d = measure(load_scene(free_scene), 3, 120, 1e-3, 0);
        std::ofstream(dir + "/data.csv") << d.csv();
    }
    ~cli_folder() { fs::remove_all(dir); }
    std::size_t files() const {
        return static_cast<std::size_t>(
            std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
    }
};

const std::string fit_args = "fit '" + free_scene + "' --data data.csv --free parameters.I1 ";

} // namespace

TEST_CASE("rotgen fit writes the fitted scene that simulate runs, and the residual plot", "[fit]") {
    cli_folder f("writes");
    const auto r = run_rotgen(fit_args + "--sigma omega1=1e-3,omega2=1e-3,omega3=1e-3 -o "
                                         "fitted.yaml --plot residuals.png",
                              f.dir);
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Contains("parameters.I1") && Contains("chi2") && Contains("correlation") &&
                          Contains("stopped: "));
    CHECK(fs::file_size(f.dir + "/residuals.png") > 1000);
    const std::string fitted = read_file(f.dir + "/fitted.yaml");
    CHECK_THAT(fitted, Contains("# covariance of parameters.I1"));
    const auto sim = run_rotgen("simulate fitted.yaml -o run.csv -q", f.dir);
    INFO(sim.err);
    CHECK(sim.status == 0);
    // the estimate written in is the truth to within a few standard errors (observed 1e-5)
    const scene_spec s = load_scene(f.dir + "/fitted.yaml");
    CHECK(std::abs(parameter_of(s, "I1") - 1.0) < 1e-3);
}

TEST_CASE("rotgen fit refuses bad data at its place and writes nothing", "[fit]") {
    cli_folder f("bad");
    const std::vector<std::pair<std::string, std::string>> cases{
        {"t,omega1,omegga2\n0.5,1,2\n", "data.csv:1:10: unknown column 'omegga2'"},
        {"omega1,omega2\n1,2\n", "data.csv:1:1: no 't' column"},
        {"t,omega1\n0.5,1\n30,1\n", "data.csv:3:1: time 30.0 is outside the scene's span"},
        {"t,omega1\n0.5,nan\n", "data.csv:2:5: 'nan' is not a number"},
        {"t,omega1,q0,q1\n0.5,1,1,0\n",
         "data.csv:1:1: the attitude needs all four columns q0, q1, q2, q3"},
        {"t,omega1\n0.5,1,2\n", "data.csv:2:1: 3 fields, the header has 2"}};
    for (const auto& [text, message] : cases) {
        std::ofstream(f.dir + "/data.csv") << text;
        const auto r = run_rotgen(fit_args + "-o fitted.yaml --plot residuals.png", f.dir);
        INFO(text);
        CHECK(r.status == 2);
        CHECK_THAT(r.err, Contains("rotgen: error: " + message));
        CHECK(f.files() == 1); // data.csv alone
    }
    std::ofstream(f.dir + "/data.csv") << "t,omega1\n0.5,1\n";
    const auto key =
        run_rotgen("fit '" + free_scene + "' --data data.csv --free parameters.I4", f.dir);
    CHECK(key.status == 2);
    CHECK_THAT(key.err, Contains("rotgen fit --free parameters.I4: unknown free key"));
}

TEST_CASE("rotgen fit that does not converge exits 3 with its last iterate in the partial file",
          "[fit]") {
    cli_folder f("partial");
    const auto r = run_rotgen(fit_args + "--max-evaluations 2 -o fitted.yaml", f.dir);
    CHECK(r.status == 3);
    CHECK_THAT(r.err, Contains("did not converge") && Contains("fitted.partial.yaml"));
    CHECK_FALSE(fs::exists(f.dir + "/fitted.yaml"));
    CHECK_THAT(read_file(f.dir + "/fitted.partial.yaml"), Contains("NOT CONVERGED"));
}

TEST_CASE("rotgen fit reports a free body's three moments as not identifiable", "[fit]") {
    cli_folder f("scale");
    const auto r = run_rotgen("fit '" + free_scene +
                                  "' --data data.csv --free parameters.I1,parameters.I2,"
                                  "parameters.I3 -o fitted.yaml",
                              f.dir);
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Contains("rotgen: error: rotgen fit --free parameters.I1,parameters.I2,"
                               "parameters.I3: the data do not determine") &&
                          Contains("common scale"));
    CHECK(f.files() == 1);
}
