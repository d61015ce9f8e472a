// rotgen — output files that appear whole or not at all, and never destroy anything.
//
// A regular file is written to a temporary beside its target (same directory, so the rename stays
// on one file system) and renamed into place only when complete: a failed or interrupted run
// never leaves a partial or corrupt file under the requested name. The target is resolved first:
//   "-"                        standard output (written at commit);
//   a symlink                  followed: its target is written, the link stays a link;
//   a FIFO, a device, ...      (anything that exists and is not a regular file) written directly;
//   one of `inputs`            refused (user_error): rotgen never overwrites a file it reads.
// Errors are user errors naming the target: "out.csv: cannot write: No such file or directory".
// Every temporary is registered with support/signals.hpp: SIGINT, SIGTERM and SIGPIPE remove them
// all and exit with 130 / 143 / 141.
#pragma once

#include "support/signals.hpp" // register_temporary, used with atomic files

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace rotgen {

class atomic_file {
  public:
    // Resolves the target and opens the temporary; throws user_error if it cannot be created or
    // if the target is one of `inputs` (paths of files the command reads).
    explicit atomic_file(std::string path, const std::vector<std::string>& inputs = {});
    atomic_file(const atomic_file&) = delete;
    atomic_file& operator=(const atomic_file&) = delete;
    ~atomic_file(); // removes the temporary unless committed

    std::ostream& stream();
    const std::string& path() const { return m_path; }
    // The file being written, for programs that write it themselves (gnuplot); empty for
    // standard output and for targets written directly.
    const std::string& temporary() const { return m_tmp; }
    bool is_stdout() const { return m_stdout; }
    // Completes the file: renames the temporary to the target, or flushes what was written
    // directly. Throws user_error on failure.
    void commit();

  private:
    std::string m_path, m_target, m_tmp;
    std::ofstream m_out;
    std::ostringstream m_buffer; // standard output: written at commit
    bool m_stdout = false, m_direct = false, m_done = false;
};

// `text` into `path`, atomically.
void write_file_atomically(const std::string& path, const std::string& text);

} // namespace rotgen
