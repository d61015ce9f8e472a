// rotgen fit — the measurements: a CSV file with a `t` column and any of the scene's recordable
// columns (omega1..3, q0..q3, the angles, Lx.., L1.., p_.., energy, ...), in any order. An empty
// field is a missing measurement; lines starting with '#' are comments (a rotgen CSV's first
// line). Quaternion columns come as the four q0..q3 together (a row gives all four or none): the
// attitude, scalar first, any sign and norm (normalised here). Times may be in any order, and
// repeated, but inside the scene's span.
#pragma once

#include "scene/scene.hpp"

#include <string>
#include <vector>

namespace rotgen {

struct measured_data {
    std::string file;
    std::vector<double> t;                   // per row, as read
    std::vector<std::string> columns;        // the measured columns (q0..q3 as "q"), in file order
    std::vector<std::vector<double>> values; // per column, per row (NaN: missing); "q": unused
    std::vector<std::array<double, 4>> q;    // per row when "q" is a column (NaN: missing)
    std::vector<int> line;                   // per row: its line in the file
    bool has_q() const;
};

// Reads and checks `path` against `scene` (its recordable columns and its span). Throws
// user_error located at the line and column of the first problem: no `t` column, an unknown or
// repeated column, a quaternion without all four components, a field that is not a number (or is
// NaN or infinite), a time outside the span, a row with too many or too few fields, no data.
measured_data read_measured(const std::string& path, const scene_spec& scene);

// The same from columns already in memory (Python's DataFrame): `names` with their values per
// row (NaN: missing), `source` naming them in messages (line = row + 2, column = column + 1).
measured_data measured_from_columns(const std::vector<std::string>& names,
                                    const std::vector<std::vector<double>>& columns,
                                    const scene_spec& scene, const std::string& source);

// The record names the columns need (q -> q0..q3), for the run that models them.
std::vector<std::string> measured_records(const measured_data& data);

} // namespace rotgen
