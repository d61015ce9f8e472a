// rotgen sweep: a member whose varied parameters make the inertia unphysical (a negative moment,
// a broken triangle inequality) is a rejected member, with its reason in summary.csv's status;
// the other members run, and the sweep exits 3 naming the rejected ones (issue 24).
#include "error_sites.hpp"
#include "support.hpp"

#include <catch2/catch.hpp>

#include <string>

using namespace rotgen::test;

namespace {

// The data lines of summary.csv, without the header.
std::vector<std::string> member_lines(const std::string& path) {
    std::vector<std::string> lines = text_lines(read_file(path));
    if (!lines.empty()) lines.erase(lines.begin());
    return lines;
}

bool ends_with(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

} // namespace

TEST_CASE("sweep: a member with an unphysical inertia is rejected with its reason",
          "[sweep][errors]") {
    // the heavy top: I1 = I2 = 1; I3 = 2 is the flat limit (allowed), 2.5 breaks I1 + I2 >= I3,
    // -0.1 is a negative moment
    const scratch_file scene("sweep_unphysical.yaml", "model: " + model_path("heavy_top") +
                                                          "\ninitial: {phi: 0, theta: 0.5, psi: "
                                                          "0, phi_dot: 0, theta_dot: 0, psi_dot: "
                                                          "5}\ntime: {end: 0.5, samples: 6}\n");
    const scratch_dir out("sweep_unphysical_out");
    const std::string lanes = GENERATE(as<std::string>{}, "", " --lanes 2");
    INFO("options:" << lanes);
    const run_result r =
        run_rotgen("sweep sweep_unphysical.yaml -j 1 -q" + lanes +
                       " --vary parameters.I3=0.5,2,2.5,-0.1 -o '" + out.path.string() + "'",
                   ROTGEN_BINARY_DIR);
    INFO(r.err);
    if (!lanes.empty() && r.status == 2 && r.err.find("--lanes") != std::string::npos) {
        WARN("built without SIMD lanes: " << r.err);
        return;
    }
    CHECK(r.status == 3);
    const std::vector<std::string> lines = member_lines((out.path / "summary.csv").string());
    REQUIRE(lines.size() == 4);
    CHECK(ends_with(lines[0], ",ok"));
    CHECK(ends_with(lines[1], ",ok"));
    const std::string why = "sweep_unphysical.yaml:1:1: rejected: with these parameter values the "
                            "inertia is not physical: ";
    CHECK(ends_with(lines[2], ",\"" + why +
                                  "principal moments (1, 1, 2.5) break the triangle inequality "
                                  "(each at most the sum of the other two): 1 + 1 < 2.5\""));
    CHECK(ends_with(lines[3], ",\"" + why + "a principal moment is negative (-0.1, 1, 1)\""));
    // a rejected member has no final values and took no step
    CHECK(lines[3].rfind("3,-0.1,,", 0) == 0);
    CHECK(r.err.find("member 2: " + why) != std::string::npos);
    CHECK(r.err.find("member 3: " + why) != std::string::npos);
}
