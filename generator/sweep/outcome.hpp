// rotgen sweep — one member's run reduced to what the ensemble keeps (its summary row and,
// optionally, its trajectory), and the summary table.
#pragma once

#include "run/engine.hpp"
#include "run/prepared.hpp"
#include "sweep/members.hpp"

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace rotgen {

struct member_outcome {
    std::vector<double> final_row; // t and the recorded columns at the last sample reached
    std::vector<double> final_sensitivities; // there, summary_layout::sensitivities (or none)
    std::vector<double> drifts;              // max |v(t) - v(t0)|, one per monitored invariant
    std::vector<double> event_times; // the first time of each scene event; NaN: it never occurred
    std::vector<double> actions;     // how many times each acting event acted (layout.acting)
    std::uint64_t steps = 0, rhs_evals = 0;
    std::string status = "ok"; // or why the member stopped (or could not start)
    bool in_lanes = false;     // run in a batch of lanes (sweep --lanes), not alone
    // With trajectories: samples x trajectory_columns(layout) (t, the recorded columns, then the
    // d(...) columns of the sensitivities), row-major; NaN past the last sample reached (and in
    // the d(...) columns of a member that started in another form, which has none).
    std::vector<double> trajectory;
    // Its line of summary.csv, formatted where the member ran (on every thread and rank at once),
    // so that the one writer only appends it.
    std::string summary_row;
    bool ok() const { return status == "ok"; }
};

// What every member's row has: the record columns (after t), the scene's events and the monitored
// invariants.
struct summary_layout {
    std::vector<std::string> columns;    // recorded columns, body_x expanded
    std::vector<std::string> events;     // the scene's events, in the scene's order
    std::vector<std::size_t> acting;     // those that act (impulse, set): actions.<name> columns
    std::vector<std::string> invariants; // energy, p_phi, ...
    // With the scene's sensitivities: d(<column>)/d(<key>), as the scene's form records them
    std::vector<std::string> sensitivities;
    std::size_t samples = 0;
};
summary_layout layout_of(const prepared_scene& prepared);
// The names of a trajectory's columns: t, the recorded columns, then the sensitivities' d(...).
std::vector<std::string> trajectory_columns(const summary_layout& layout);

// Runs one member. A user error of this member (its values cannot start a run) and a run that
// stops early are outcomes (status), not exceptions.
member_outcome run_one(const prepared_scene& prepared, const summary_layout& layout,
                       const member_values& values, bool keep_trajectory);

// The outcome of a member's run.
member_outcome outcome_of(const prepared_scene& prepared, const summary_layout& layout,
                          const run_result& r, bool keep_trajectory);

// summary.csv: member, the keys as written, final.t, final.<column>..., with sensitivities
// final.d(<column>)/d(<key>)..., event.<name>... (the time
// of the event's first occurrence, empty if none), drift.<invariant>..., steps, rhs_evals, status.
// Numbers with 17 significant digits; a status with a comma or a quote is quoted (RFC 4180).
void write_summary_header(std::ostream& os, const sweep_plan& plan, const summary_layout& layout);
// Member m's row (`row`: its values of the varied keys).
void write_summary_row(std::ostream& os, std::size_t m, const std::vector<double>& row,
                       const summary_layout& layout, const member_outcome& outcome);
// The same row as a string (for member_outcome::summary_row).
std::string summary_row_of(std::size_t m, const std::vector<double>& row,
                           const summary_layout& layout, const member_outcome& outcome);

} // namespace rotgen
