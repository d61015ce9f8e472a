// rotgen sweep across MPI ranks: how the groups of members are shared (each rank's static block,
// then guided chunks from one atomic counter). Pure arithmetic on the counter's values, apart
// from MPI, so that it is tested without ranks; distribute_mpi.cpp holds the counter itself.
#pragma once

#include "sweep/distribute.hpp"

#include <algorithm>
#include <cstddef>
#include <optional>
#include <utility>

namespace rotgen {

using group_range = std::pair<std::size_t, std::size_t>; // groups first .. second-1

// How the groups are shared by `ranks` ranks of `jobs` threads each, rank 0 holding at most
// `window` members' outcomes.
struct sharing {
    member_groups gs;
    std::size_t window, ranks, jobs;
    // Groups in a chunk or a block, at most: every rank's queue (jobs + 1 chunks) fits half the
    // window together, so that ranks rarely wait for the writer (and a chunk always fits); no
    // bound when the window holds the whole sweep.
    std::size_t most() const {
        if (window >= gs.count) return std::max<std::size_t>(1, gs.size());
        return std::max<std::size_t>(1, window / gs.group / (2 * ranks * (jobs + 1)));
    }
    // Each rank's static block: a quarter of the sweep, shared equally.
    std::size_t block() const {
        return std::clamp<std::size_t>(gs.size() / (4 * ranks), 1, most());
    }
    group_range first_block(std::size_t rank) const {
        const std::size_t b = block();
        return {std::min(gs.size(), rank * b), std::min(gs.size(), rank * b + b)};
    }
    std::size_t dynamic_start() const { return std::min(gs.size(), ranks * block()); }
    // Guided: the groups not yet handed out (`next`: the counter) over twice the chunks every rank
    // may hold (its queue keeps jobs + 1), at least 1: a rank then holds at most half its share of
    // what is left, so that a slower rank (its members costlier, its cores shared) cannot keep the
    // others waiting at the end for long.
    std::size_t chunk(std::size_t next) const {
        const std::size_t left = gs.size() - std::min(gs.size(), next);
        return std::clamp<std::size_t>(left / (2 * ranks * (jobs + 1)), 1, most());
    }
};

// The next chunk from `counter`, the counter every rank takes groups from (next() reads it;
// fetch_add(n) takes n groups and returns the value before), or none once every group is handed
// out. Its size comes from the counter as it is now: from a value this rank saw long ago, a late
// chunk would be as large as an early one and leave the other ranks idle at the end.
template <class Counter>
std::optional<group_range> take_chunk(const sharing& sh, Counter& counter) {
    const std::size_t n = sh.chunk(counter.next()), first = counter.fetch_add(n);
    if (first >= sh.gs.size()) return std::nullopt;
    return group_range{first, std::min(sh.gs.size(), first + n)};
}

} // namespace rotgen
