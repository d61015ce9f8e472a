// rotgen sweep — the files of a sweep, written while the members run, in member order, so that a
// sweep of any size runs in bounded memory (sweep/in_order.hpp holds at most a window of
// outcomes; this writer holds at most a chunk of rows and 256 members' samples). They are written
// under the journal's partial names (sweep/journal.hpp) a chunk of members at a time, and renamed
// to DIR/summary.csv and DIR/trajectories.h5 by commit().
//
// The files of a sweep are a set (sweep_set_files): commit() removes those of the set that this
// run did not write, so that a folder never holds files of two sweeps (a summary.csv beside an
// earlier sweep's trajectories.h5); until then the earlier sweep's files stay as they were.
#pragma once

#include "scene/scene.hpp"
#include "sweep/journal.hpp"
#include "sweep/members.hpp"
#include "sweep/outcome.hpp"
#include "sweep/trajectories.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace rotgen {

// The names of the files a sweep may write in its folder (final and partial).
const std::vector<std::string>& sweep_set_files();

// What a sweep of `members` members will write, in bytes (summary.csv about 24 bytes a number;
// trajectories.h5 8 bytes a number, exactly, plus 64 KiB), computed before any derivation.
std::uint64_t estimated_output(const scene_spec& scene, const sweep_plan& plan, std::size_t members,
                               bool trajectories);
// Refuses (user_error naming DIR, with the estimate) an output larger than the free space of the
// file system that holds DIR (or, if DIR does not exist yet, its parent).
void check_room(const std::string& dir, std::uint64_t bytes, std::size_t members);

struct writer_setup {
    std::string dir;
    bool made_dir = false;     // this run created DIR (an interrupted run removes it if empty)
    bool trajectories = false; // also DIR/trajectories.h5
    std::string hash;          // the journal's stamp (journal_hash)
    journal_found resume;      // the journal to go on from (exists: --resume found one)
    std::size_t chunk = 1;     // members a journal chunk (a multiple of the lanes' width)
};

class sweep_writer {
  public:
    // Starts the journal (or goes on with setup.resume's). Throws user_error.
    sweep_writer(const writer_setup& setup, const scene_spec& scene, const sweep_plan& plan,
                 const member_table& table, const summary_layout& layout);
    sweep_writer(const sweep_writer&) = delete;
    sweep_writer& operator=(const sweep_writer&) = delete;
    ~sweep_writer(); // without commit(): the journal as of its last chunk (journal_abandon)

    // The next member's outcome (members come in order), its summary row formatted where it ran.
    void add(std::size_t member, member_outcome&& outcome);
    // Completes the files, renames them into place and removes the set's other files.
    void commit();

    std::size_t first() const { return m_first; }       // members the journal held at the start
    std::size_t members() const { return m_members; }   // members added by this run
    std::size_t failed() const { return m_failed; }     // failed members, the journal's too
    std::size_t in_lanes() const { return m_in_lanes; } // members added that ran in lanes
    std::uint64_t steps() const { return m_steps; }
    std::uint64_t rhs_evals() const { return m_evals; }
    // The first ten failed members and their status.
    const std::vector<std::pair<std::size_t, std::string>>& failures() const { return m_failures; }
    std::string summary_path() const { return m_setup.dir + "/summary.csv"; }
    std::string trajectories_path() const { return m_setup.dir + "/trajectories.h5"; }

  private:
    void start(const trajectory_file& header, const sweep_plan& plan); // a new journal
    void go_on(const trajectory_file& header);                         // setup.resume's
    void end_chunk(); // the chunk's samples flushed, then its rows appended: a journal point
    void forget_removed_stamp() const; // the interrupt line no longer names a removed stamp
    writer_setup m_setup;
    journal_names m_names;
    const member_table& m_table;
    const summary_layout& m_layout;
    int m_fd = -1;      // summary.partial.csv, appended
    std::string m_rows; // the chunk's rows
    std::unique_ptr<trajectory_stream> m_h5;
    std::uint64_t m_bytes = 0; // summary.partial.csv's bytes on disk
    std::size_t m_first = 0, m_members = 0, m_failed = 0, m_chunks = 0, m_in_lanes = 0;
    long m_interrupt_after = -1; // the tests' hook
    std::uint64_t m_steps = 0, m_evals = 0;
    std::vector<std::pair<std::size_t, std::string>> m_failures;
};

} // namespace rotgen
