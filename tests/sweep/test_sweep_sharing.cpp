// rotgen sweep across MPI ranks: how the groups are shared, without ranks. Every rank takes
// chunks from one counter (sweep/sharing.hpp); here a plain number plays the counter, and the
// calls in between a rank's two chunks play the other ranks.
#include "sweep/sharing.hpp"

#include <catch2/catch.hpp>

#include <cstddef>
#include <vector>

using namespace rotgen;

namespace {

struct plain_counter {
    std::size_t value;
    std::size_t next() const { return value; }
    std::size_t fetch_add(std::size_t n) {
        value += n;
        return value - n;
    }
};

} // namespace

TEST_CASE("a late chunk is sized from the groups left now, not from those its rank saw before",
          "[sweep][mpi]") {
    // the 16-core benchmark's layout: 16,384 members, 16 ranks of one thread, no window bound
    const sharing sh{{16384, 1}, 16384, 16, 1};
    REQUIRE(sh.dynamic_start() == 16 * 256); // a quarter of the sweep in static blocks
    plain_counter counter{sh.dynamic_start()};
    const auto early = take_chunk(sh, counter);
    REQUIRE(early);
    CHECK(early->second - early->first == (16384 - 4096) / 64); // 192: over 16 ranks x 2 x 2 chunks
    while (counter.value < 16000) // the other ranks take chunks meanwhile
        REQUIRE(take_chunk(sh, counter));
    const std::size_t left = 16384 - counter.value;
    const auto late = take_chunk(sh, counter);
    REQUIRE(late);
    // from the value this rank saw after its early chunk (4,288) it would be 189 groups, nearly
    // half of the at most 384 left: one rank would run them while fifteen wait
    CHECK(late->second - late->first == std::max<std::size_t>(1, left / 64));
    CHECK(late->second - late->first < 6);
}

TEST_CASE("the chunks cover every group after the static blocks once, and the last are single",
          "[sweep][mpi]") {
    const sharing sh{{1000, 8}, 1000, 3, 2}; // groups of 8 lanes: 125 groups
    std::vector<int> taken(sh.gs.size(), 0);
    for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t g = sh.first_block(r).first; g < sh.first_block(r).second; ++g)
            ++taken[g];
    plain_counter counter{sh.dynamic_start()};
    std::vector<std::size_t> sizes;
    while (const auto c = take_chunk(sh, counter)) {
        for (std::size_t g = c->first; g < c->second; ++g)
            ++taken[g];
        sizes.push_back(c->second - c->first);
    }
    CHECK(std::count(taken.begin(), taken.end(), 1) == 125);
    REQUIRE(sizes.size() > 4);
    CHECK(sizes.front() == (125 - 30) / 18); // 3 blocks of 10; then the rest over 2 x 3 x (2 + 1)
    CHECK(sizes.back() == 1);
    CHECK(std::is_sorted(sizes.rbegin(), sizes.rend())); // guided: never growing
}

TEST_CASE("with a short window on rank 0 no chunk outgrows every rank's share of half of it",
          "[sweep][mpi]") {
    const sharing sh{{100000, 1}, 4000, 4, 3}; // half the window over 4 ranks' queues of 4 chunks
    REQUIRE(sh.most() == 4000 / (2 * 4 * 4));
    plain_counter counter{sh.dynamic_start()};
    std::size_t largest = 0;
    while (const auto c = take_chunk(sh, counter))
        largest = std::max(largest, c->second - c->first);
    CHECK(largest == 125);
    CHECK(sh.block() <= 125);
}
