// rotgen sweep — a group of neighbouring members run together: in a batch of SIMD lanes
// (run/lanes.hpp) when the sweep has lane kernels (those a batch cannot carry run alone), else
// each alone (run_one). `rotgen sweep` and the Python module's rotgen.sweep run members through it.
#pragma once

#include "run/lanes.hpp"
#include "sweep/members.hpp"
#include "sweep/outcome.hpp"

#include <cstddef>
#include <vector>

namespace rotgen {

// What every member of a sweep runs on (references, kept by the caller).
struct sweep_members {
    const prepared_scene& prepared;
    const summary_layout& layout;
    const sweep_plan& plan;
    const member_table& table;
    const lane_kernels* lanes = nullptr; // null: every member alone
    bool trajectories = false;           // keep each member's samples (member_outcome)
};

// Members first .. first+count-1 of s.table, on the scene's values `base` with each member's row
// substituted; in_lanes says which of them ran in the batch.
std::vector<member_outcome> run_neighbours(const sweep_members& s, const member_values& base,
                                           std::size_t first, std::size_t count);

} // namespace rotgen
