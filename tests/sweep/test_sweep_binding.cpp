// rotgen sweep: the cores a rank's threads get when the launcher bound it to too few
// (sweep/binding.hpp). The choice is a function of the allowed CPUs, the cores they form and the
// node's ranks; the rebinding itself is tested through mpirun (tests/sweep/affinity.sh).
#include "support/error.hpp"
#include "sweep/binding.hpp"
#include "sweep/parallel.hpp"

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

std::vector<int> alone(int c) {
    return {c};
}

// 16 cores of one hardware thread each (the virtual machines measured)
std::vector<core_cpus> sixteen() {
    return group_by_core(range(0, 16), alone);
}

} // namespace

TEST_CASE("each rank of a node gets a block of cores of its own when every rank's threads fit",
          "[sweep][binding]") {
    // mpirun -n 2 -j 8 on 16 cores: as --map-by slot:PE=8 would place them
    CHECK(cpus_for_rank(sixteen(), 8, 0, 2) == range(0, 8));
    CHECK(cpus_for_rank(sixteen(), 8, 1, 2) == range(8, 8));
    // 4 ranks of 4 threads
    CHECK(cpus_for_rank(sixteen(), 4, 3, 4) == range(12, 4));
    // 5 threads on 16 cores leave one core spare
    CHECK(cpus_for_rank(sixteen(), 5, 2, 3) == range(10, 5));
    // a cpuset with holes: the blocks are of the allowed cores, in order
    const auto holes = group_by_core({2, 3, 5, 7, 11, 13}, alone);
    CHECK(cpus_for_rank(holes, 3, 1, 2) == std::vector<int>{7, 11, 13});
}

TEST_CASE("a rank's block holds whole cores with their hardware threads", "[sweep][binding]") {
    // 4 cores of 2 threads, numbered as on most Intel machines (CPU c and c+4 share a core)
    const auto apart = [](int c) { return std::vector<int>{c % 4, c % 4 + 4}; };
    const std::vector<core_cpus> intel = group_by_core(range(0, 8), apart);
    REQUIRE(intel.size() == 4);
    CHECK(intel[1] == std::vector<int>{1, 5});
    CHECK(cpus_for_rank(intel, 2, 0, 2) == std::vector<int>{0, 1, 4, 5});
    CHECK(cpus_for_rank(intel, 2, 1, 2) == std::vector<int>{2, 3, 6, 7});
    // numbered side by side (CPU 2k and 2k+1 share a core)
    const auto side = [](int c) { return std::vector<int>{c - c % 2, c - c % 2 + 1}; };
    CHECK(cpus_for_rank(group_by_core(range(0, 8), side), 2, 1, 2) == range(4, 4));
    // a sibling the cpuset withholds is left out
    CHECK(group_by_core({0, 1, 2, 3, 4}, apart).back() == std::vector<int>{3});
}

TEST_CASE("the ranks of a node share all its allowed cores when their threads do not fit",
          "[sweep][binding]") {
    CHECK(cpus_for_rank(sixteen(), 8, 0, 3) == range(0, 16)); // 24 threads
    CHECK(cpus_for_rank(sixteen(), 8, 2, 3) == range(0, 16));
    CHECK(cpus_for_rank(sixteen(), 32, 0, 1) == range(0, 16)); // more threads than cores
    CHECK(cpus_for_rank(group_by_core({4, 6}, alone), 2, 1, 2) == std::vector<int>{4, 6});
    // 2 ranks of 4 threads on 4 cores of 2 threads: the cores do not hold them, the CPUs are shared
    const auto apart = [](int c) { return std::vector<int>{c % 4, c % 4 + 4}; };
    CHECK(cpus_for_rank(group_by_core(range(0, 8), apart), 4, 1, 2) == range(0, 8));
}

TEST_CASE("a CPU list in the kernel's format is read, and anything else is not",
          "[sweep][binding]") {
    CHECK(cpu_list("0-3,8,10-11") == std::vector<int>{0, 1, 2, 3, 8, 10, 11});
    CHECK(cpu_list("5\n") == std::vector<int>{5});
    CHECK(cpu_list("0,16") == std::vector<int>{0, 16});
    CHECK(cpu_list("").empty());
    CHECK(cpu_list("3-1").empty());
    CHECK(cpu_list("a").empty());
    CHECK(cpu_list("1+2").empty());
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

TEST_CASE("a CPU mask's bits are counted, and this process's mask holds its cores",
          "[sweep][binding]") {
    CHECK(cpus_in({0xff, 0x01, 0x00, 0x80}) == 10);
    CHECK(cpus_in({}) == 0);
    CHECK(cpus_in(cpu_mask()) == all_cores());
}
