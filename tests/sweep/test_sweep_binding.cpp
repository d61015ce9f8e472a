// rotgen sweep: the cores a rank's threads get when the launcher bound it to too few
// (sweep/binding.hpp). The choice is a function of the allowed cores and the node's ranks; the
// rebinding itself is tested through mpirun (tests/sweep/affinity.sh).
#include "support/error.hpp"
#include "sweep/binding.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <vector>

using namespace rotgen;

namespace {

std::vector<int> range(int first, int count) {
    std::vector<int> r;
    for (int c = first; c < first + count; ++c)
        r.push_back(c);
    return r;
}

} // namespace

TEST_CASE("each rank of a node gets a block of cores of its own when every rank's threads fit",
          "[sweep][binding]") {
    const std::vector<int> sixteen = range(0, 16);
    // mpirun -n 2 -j 8 on 16 cores: as --map-by slot:PE=8 would place them
    CHECK(cores_for_rank(sixteen, 8, 0, 2) == range(0, 8));
    CHECK(cores_for_rank(sixteen, 8, 1, 2) == range(8, 8));
    // 4 ranks of 4 threads
    CHECK(cores_for_rank(sixteen, 4, 3, 4) == range(12, 4));
    // a cpuset with holes: the blocks are of the allowed cores, in order
    CHECK(cores_for_rank({2, 3, 5, 7, 11, 13}, 3, 1, 2) == std::vector<int>{7, 11, 13});
    // 5 threads on 16 cores leave one core spare
    CHECK(cores_for_rank(sixteen, 5, 2, 3) == range(10, 5));
}

TEST_CASE("the ranks of a node share all its allowed cores when their threads do not fit",
          "[sweep][binding]") {
    const std::vector<int> sixteen = range(0, 16);
    CHECK(cores_for_rank(sixteen, 8, 0, 3) == sixteen); // 24 threads
    CHECK(cores_for_rank(sixteen, 8, 2, 3) == sixteen);
    CHECK(cores_for_rank(sixteen, 32, 0, 1) == sixteen); // one rank, more threads than cores
    CHECK(cores_for_rank({4, 6}, 2, 1, 2) == std::vector<int>{4, 6});
}

TEST_CASE("ROTGEN_BINDING takes auto or keep and names any other value", "[sweep][binding]") {
    ::unsetenv("ROTGEN_BINDING");
    CHECK(binding_of_environment() == binding_policy::automatic);
    ::setenv("ROTGEN_BINDING", "keep", 1);
    CHECK(binding_of_environment() == binding_policy::keep);
    ::setenv("ROTGEN_BINDING", "auto", 1);
    CHECK(binding_of_environment() == binding_policy::automatic);
    ::setenv("ROTGEN_BINDING", "none", 1);
    CHECK_THROWS_WITH(binding_of_environment(),
                      Catch::Contains("unknown binding policy; use keep"));
    try {
        binding_of_environment();
    } catch (const user_error& e) {
        CHECK(e.message().rfind("ROTGEN_BINDING=none: ", 0) == 0);
    }
    ::unsetenv("ROTGEN_BINDING");
}
