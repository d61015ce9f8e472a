// rotgen — output files that appear whole or not at all.
//
// Every file rotgen writes goes to a temporary beside its target (same directory, so the rename
// stays on one file system) and is renamed into place only when complete: a failed or
// interrupted run never leaves a partial or corrupt file under the requested name. Errors are
// user errors naming the target: "out.csv: cannot write: No such file or directory".
#pragma once

#include <fstream>
#include <string>

namespace rotgen {

class atomic_file {
  public:
    // Opens the temporary; throws user_error if it cannot be created.
    explicit atomic_file(std::string path);
    atomic_file(const atomic_file&) = delete;
    atomic_file& operator=(const atomic_file&) = delete;
    ~atomic_file(); // removes the temporary unless committed

    std::ostream& stream() { return m_out; }
    const std::string& path() const { return m_path; }
    const std::string& temporary() const { return m_tmp; }
    // Closes the temporary and renames it to the target; throws user_error on failure.
    void commit();

  private:
    std::string m_path, m_tmp;
    std::ofstream m_out;
    bool m_done = false;
};

// `text` into `path`, atomically.
void write_file_atomically(const std::string& path, const std::string& text);

} // namespace rotgen
