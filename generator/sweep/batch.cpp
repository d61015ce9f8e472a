#include "sweep/batch.hpp"

#include <optional>

namespace rotgen {

std::vector<member_outcome> run_neighbours(const sweep_members& s, const member_values& base,
                                           std::size_t first, std::size_t count) {
    std::vector<member_values> values;
    for (std::size_t m = first; m < first + count; ++m)
        values.push_back(member_of(s.plan, base, s.table.row(m)));
    std::vector<member_outcome> out;
    if (!s.lanes) {
        for (const auto& v : values)
            out.push_back(run_one(s.prepared, s.layout, v, s.trajectories));
        return out;
    }
    const std::vector<std::optional<run_result>> results = run_lanes(s.prepared, *s.lanes, values);
    for (std::size_t k = 0; k < count; ++k) {
        out.push_back(results[k] ? outcome_of(s.prepared, s.layout, *results[k], s.trajectories)
                                 : run_one(s.prepared, s.layout, values[k], s.trajectories));
        out.back().in_lanes = results[k].has_value();
    }
    return out;
}

} // namespace rotgen
