// rotgen sweep — the journal: what an interrupted sweep keeps, and what `--resume` reads.
//
// A sweep writes its files under partial names while it runs, in member order, and renames them
// when it completes:
//   DIR/sweep.partial             the journal's stamp: a hash of the scene file, the model file and
//                                 the options that change the files (--vary, --trajectories,
//                                 --lanes); written first;
//   DIR/summary.partial.csv       summary.csv's header and the rows of the members finished so far,
//                                 appended a chunk of members at a time;
//   DIR/trajectories.partial.h5   with --trajectories: trajectories.h5 with every member's samples
//                                 up to the last chunk written (flushed before the chunk's rows).
// SIGINT and SIGTERM (a scheduler ends a job with SIGTERM) keep the journal as of its last chunk
// (summary.partial.csv cut back to it) and say so in one line, or, if no member had finished,
// remove the journal (and DIR if this run made it) and print "interrupted; nothing written"; then
// the process exits with 130 / 143. `--resume` goes on after the journal's last member.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rotgen {

struct journal_names {
    std::string dir, stamp, summary, trajectories;
};
journal_names journal_in(const std::string& dir);

// The stamp's hash: of the scene and model files' text and the options that change the files.
std::string journal_hash(const std::string& scene_file, const std::string& model_file,
                         const std::vector<std::string>& vary, bool trajectories, unsigned lanes);

// An earlier run's journal in DIR, as found: the hash, and the members its summary holds (whole
// rows only) and the bytes of its header and those rows.
struct journal_found {
    bool exists = false;
    std::string hash;
    std::size_t members = 0, failed = 0; // failed: rows whose status is not ok
    std::uint64_t bytes = 0;
};
// Counts whole chunks of `chunk` rows only (or all `count` members). Throws user_error for a
// journal that cannot be read (a stamp without its summary, a row out of member order).
journal_found read_journal(const journal_names& names, std::size_t chunk, std::size_t count);

// What the signal handler (and a run that fails) does with the journal: watched from the moment
// the journal's files exist until they are renamed into place.
// Before the journal exists: an interruption prints "interrupted; nothing written".
void journal_not_yet();
// On an MPI rank other than 0, which keeps no journal: an interruption says nothing (rank 0 says
// it once; and mpirun ends the others with SIGTERM when rank 0 exits with an error it reported).
void journal_elsewhere();
void journal_watch(const journal_names& names, int summary_fd, std::uint64_t bytes,
                   std::size_t members, bool made_dir);
void journal_committed(std::uint64_t bytes, std::size_t members); // a chunk is whole on disk
void journal_unwatch();
// Cuts the summary back to its last whole chunk, or removes the journal (and DIR if this run made
// it) if no member finished; with a signal (sig > 0), prints the one line. Async-signal-safe.
void journal_abandon(int sig);

} // namespace rotgen
