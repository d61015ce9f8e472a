// rotgen sweep --trajectories — every member's samples in one HDF5 file (the HDF5 C library):
//
//   /trajectories    double [member, sample, column]: t and the recorded columns at each sample
//                    time; NaN past the last sample a member reached (a failed member)
//     attributes     columns (strings: t, then the recorded columns), varied_keys (strings, as
//                    written), scene (the scene file's text), scene_file
//   /varied_values   double [member, key]: each member's values of the varied keys
//                    (a dataset: HDF5 keeps an attribute under 64 KiB; attribute keys names them)
//
// The file is the same byte for byte on every run (no object timestamps), written to a temporary
// beside it and renamed into place.
#pragma once

#include <string>
#include <vector>

namespace rotgen {

struct trajectory_file {
    std::vector<std::string> columns; // t, then the recorded columns
    std::vector<std::string> keys;    // the varied keys, as written
    std::string scene_text, scene_file;
    std::size_t members = 0, samples = 0;
    const std::vector<std::vector<double>>* values = nullptr; // [member][key]
    // member m's samples x columns, row-major (each of samples * columns.size() values)
    std::vector<const std::vector<double>*> data;
};

// Writes `path` atomically. Throws user_error if it cannot be written.
void write_trajectories(const std::string& path, const trajectory_file& f);

} // namespace rotgen
