// rotgen bench: the best configuration per accuracy, measured and interpolated, and the names the
// tables and plots give configurations.
#pragma once

#include "bench/driver.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace rotgen::bench {

// The method of a configuration as the tables and plots name it: an adaptive method run with a
// fixed step (rotgen's DOP853, Odeint's Fehlberg 7(8)) is a curve of its own, "dop853 fixed".
std::string method_key(const result_row& r);

// "dop853", "odeint rkf78 fixed", ...
std::string method_title(const result_row& r);

// The name of a configuration, for the tables ("—" for none).
std::string config_name(const result_row* r);

// Configurations are compared at matched accuracy only (issue 14: `bench --quick` ranked a run
// with error 1e-4 against one with 1e-12 as if they had done the same work). At an error level L
// a measured configuration is ranked if its error e is within the decade below L,
//     L/10 < e <= L,
// so that the errors of any two configurations ranked together differ by less than 10x; a
// curve is also ranked at L where two of its neighbouring points straddle L (cost interpolated
// at L exactly). A run more accurate than L/10 is ranked at its own level, not at L.
bool matched_accuracy(double error, double level);

// The text the summaries give for that rule.
inline constexpr const char* matched_accuracy_rule =
    "configurations are ranked only at matched accuracy: at an error level L a run counts if "
    "its error is in (L/10, L], or its curve is interpolated at L between two runs that "
    "straddle L";

// The fastest configuration at an error level (matched accuracy): a measured point, per kind
// of peer.
struct best_entry {
    const result_row* rotgen = nullptr;
    const result_row* peer = nullptr;
};

// The time (and RHS evaluations) a configuration's curve needs to reach an error level. A curve
// that never lands in the decade below the level nor straddles it, but has runs more accurate
// than a tenth of it (a split method that is exact up to rounding on a free body: every run at
// 3e-15), still competes, with its cheapest such run: `beyond` is that run's error, and the time
// is an upper bound of the curve's cost at the level.
struct reach {
    std::string curve;
    double time = NAN, rhs = NAN;
    bool peer = false;
    double beyond = NAN; // NaN: matched or interpolated at the level
};

// Why a side (rotgen or peer) has no entry at a level: the most accurate run of that side
// ("best reached 2e-12 (rotgen dop853 double lagrangian)"), or that it has no successful run.
std::string why_none(const std::vector<result_row>& rows, bool peer, double level);

// "1.2 us (curve)", with ", an upper bound: it ran to 3e-15" when `beyond` is set.
std::string reach_text(const reach& r);

struct bench_summary {
    std::vector<double> levels;                   // 1e-3 .. 1e-13
    std::vector<best_entry> best;                 // per level
    std::vector<std::pair<reach, reach>> reached; // (rotgen, peer) per level
};

// The summary of the rows (which must outlive it).
bench_summary summarise(const std::vector<result_row>& rows);

// The time the curve of row `r` (its method, scalar and form) needs to reach `level`,
// interpolated as in the interpolated table; NaN time when it does not get there.
reach curve_reach(const std::vector<result_row>& rows, const result_row& r, double level);

// The fewest RHS evaluations of a method (double, main form) at an error level (matched
// accuracy).
const result_row* fewest(const std::vector<result_row>& rows, const std::string& peer,
                         const std::string& method, double level);

} // namespace rotgen::bench
