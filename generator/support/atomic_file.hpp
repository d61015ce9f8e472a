// rotgen — output files that appear whole or not at all, and never destroy anything.
//
// A regular file is written to a temporary beside its target (same directory, so the rename stays
// on one file system) and renamed into place only when complete: a failed or interrupted run
// never leaves a partial or corrupt file under the requested name. The target is resolved first:
//   "-"                        standard output (written at commit);
//   a symlink                  followed: its target is written, the link stays a link;
//   a FIFO, a device, ...      (anything that exists and is not a regular file) written directly,
//                              at commit;
//   one of `inputs`            refused (user_error): rotgen never overwrites a file it reads.
// Errors are user errors naming the target: "out.csv: cannot write: No such file or directory",
// "standard output: cannot write: No space left on device".
// Every temporary is registered with support/signals.hpp: SIGINT, SIGTERM and SIGPIPE remove them
// all and exit with 130 / 143 / 141.
//
// A command with several outputs commits them together through an output_set, so that exit 2
// leaves no file: each atomic_file hands its complete temporary (or, for a stream, its text) to
// the set, and the set's commit() writes the streams first (standard output and devices cannot be
// renamed: each is written, flushed and checked), then renames every temporary. A stream that
// fails stops the commit before any rename, and the set's destructor removes the temporaries; a
// stream written before the one that failed keeps what it got (it cannot be taken back).
//
//   output_set outputs;
//   atomic_file csv("run.csv", inputs), page("run.html", inputs);
//   ... csv.stream() << ...; page.stream() << ...;
//   csv.commit(outputs); page.commit(outputs);
//   outputs.commit(); // both appear, or neither
#pragma once

#include "support/signals.hpp" // register_temporary, used with atomic files

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace rotgen {

class output_set {
  public:
    output_set() = default;
    output_set(const output_set&) = delete;
    output_set& operator=(const output_set&) = delete;
    ~output_set(); // removes the temporaries not committed

    // A complete temporary, renamed to `target` at commit; `shown` names it in messages.
    void add_file(const std::string& temporary, const std::string& target,
                  const std::string& shown);
    // `text` for standard output ("-") or for a stream `path` (a device, a FIFO), written at
    // commit before any rename, in the order added.
    void add_stream(const std::string& path, std::string text);
    // Writes the streams (each flushed and checked), then renames the files, in the order added.
    // Throws user_error naming the first output that fails.
    void commit();
    // commit() in two steps, for a command that prints what it wrote on standard output between
    // them (that line is an output too: checked before any file appears).
    void commit_streams();
    void commit_files();

  private:
    struct file {
        std::string temporary, target, shown;
    };
    struct stream {
        std::string path, text;
    };
    std::vector<file> m_files;
    std::vector<stream> m_streams;
};

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
    // Completes the file now: renames the temporary to the target, or writes the stream.
    // Throws user_error on failure.
    void commit();
    // Completes the temporary and hands it (or the stream's text) to `outputs`, which commits it
    // with the others. Throws user_error when the temporary cannot be completed.
    void commit(output_set& outputs);

  private:
    std::string m_path, m_target, m_tmp;
    std::ofstream m_out;
    std::ostringstream m_buffer; // standard output, a device, a FIFO: written at commit
    bool m_stdout = false, m_direct = false, m_done = false;
};

// `text` into `path`, atomically.
void write_file_atomically(const std::string& path, const std::string& text);

} // namespace rotgen
