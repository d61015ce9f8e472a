// rotgen sweep --trajectories — every member's samples in one HDF5 file (the HDF5 C library):
//
//   /trajectories    double [member, sample, column]: t and the recorded columns at each sample
//                    time, then with the scene's sensitivities the d(<column>)/d(<key>) columns
//                    (summary.csv's final.d(...) at every sample); NaN past the last sample a
//                    member reached (a failed member)
//     attributes     columns (strings: t, the recorded columns, the d(...) columns), varied_keys
//                    (strings, as written), scene (the scene file's text), scene_file
//   /varied_values   double [member, key]: each member's values of the varied keys
//                    (a dataset: HDF5 keeps an attribute under 64 KiB; attribute keys names them)
//
// The file is the same byte for byte on every run (no object timestamps).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace rotgen {

struct trajectory_file {
    std::vector<std::string> columns; // t, then the recorded columns
    std::vector<std::string> keys;    // the varied keys, as written
    std::string scene_text, scene_file;
    std::size_t members = 0, samples = 0;
};

using values_of_members = std::function<std::vector<double>(std::size_t first, std::size_t n)>;

// The file written as the members finish, in member order, a few hundred members a write. It is
// created whole at the start (the attributes, /varied_values, and /trajectories allocated in
// full) and flushed: from then on only the samples of /trajectories are written, in place, so that
// after flush() the file on disk is a valid HDF5 file whatever happens to the process, and a run
// that goes on with it (reopen) gives the same bytes as one that never stopped.
class trajectory_stream {
  public:
    // Creates `path`; values(first, n): the varied values of members first .. first+n-1,
    // row-major [member, key]. Throws user_error.
    trajectory_stream(std::string path, trajectory_file header, const values_of_members& values);
    // Opens `path`, written by an interrupted run of the same sweep, to go on at member `next`.
    trajectory_stream(std::string path, trajectory_file header, std::size_t next);
    trajectory_stream(const trajectory_stream&) = delete;
    trajectory_stream& operator=(const trajectory_stream&) = delete;
    ~trajectory_stream(); // closes the file

    // The next member's samples x columns, row-major (shorter: NaN-padded).
    void add(const std::vector<double>& samples);
    // Writes the members added and flushes the file to disk.
    void flush();
    // Writes the members added and closes the file. Throws user_error.
    void close();
    const std::string& path() const { return m_path; }
    struct h5; // the HDF5 handles (trajectories.cpp)

  private:
    void write_buffered();
    std::string m_path;
    trajectory_file m_header;
    std::unique_ptr<h5> m_h5;
    std::vector<double> m_buffer; // members not yet written
    std::size_t m_written = 0, m_buffered = 0;
};

} // namespace rotgen
