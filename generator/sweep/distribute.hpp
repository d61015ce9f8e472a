// rotgen sweep across processes — under `mpirun -n R rotgen sweep ...` (built with ROTGEN_MPI) the
// R ranks share the groups of members (a group: `--lanes` neighbours, else one member) with no
// coordinator in the way of the work:
// - each rank starts on a static block of its own (rank r: groups r*b .. r*b+b-1; b a quarter of
//   the sweep over R, less where rank 0's window is short), asked of no one;
// - the rest is handed out by an atomic counter in an MPI window on rank 0 (MPI_Fetch_and_op,
//   MPI_SUM, passive target: on one node, or with a network's RDMA atomics, rank 0 does nothing
//   to serve it; elsewhere its main thread's MPI calls, every millisecond, move it on), in chunks
//   that shrink as the counter nears the end (guided: the groups left, read from the counter just
//   before, over twice the chunks every rank may hold, at least 1), so that the tail balances cheap
//   and expensive members;
// - MPI_THREAD_FUNNELED: only each rank's main thread calls MPI. It fetches chunks ahead into a
//   local queue (kept `jobs` + 1 chunks deep) that the rank's threads take groups from, so that a
//   thread never waits for work longer than one fetch; it sends the outcomes its threads finished
//   to rank 0 (MPI_Isend, messages of at most 1 MiB, pack/unpack), and on rank 0 it receives the
//   others' outcomes into `in_order`, which alone writes the files: the same byte for byte as a
//   one-process run's. Rank 0 takes a message as soon as it sees it (MPI_Imrecv) and delivers it
//   when it has arrived, one message between two refills of its own queue, so that its threads
//   never wait for a transfer. The main thread sleeps between rounds (1 ms, woken when its queue
//   runs low; while a message it sends or takes is on its way, 50 us at first, doubled each time
//   up to 1 ms: a large one moves only in the calls of both ends).
// - Memory stays bounded: rank 0 publishes in the window how many members it has written (the
//   front of `in_order`), and a rank lets its threads start a chunk only when the chunk's members
//   fit the window of outcomes rank 0 may hold (front + window); chunks are sized so that every
//   rank's queue together holds at most half of it.
// Started without mpirun (or built without MPI) it is one process.
#pragma once

#include "sweep/in_order.hpp"
#include "sweep/outcome.hpp"
#include "sweep/work_clock.hpp"

#include <algorithm>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace rotgen {

class mpi_session {
  public:
    mpi_session(); // MPI_Init_thread when started by mpirun (its environment says so)
    mpi_session(const mpi_session&) = delete;
    mpi_session& operator=(const mpi_session&) = delete;
    ~mpi_session(); // MPI_Finalize
    int rank() const { return m_rank; }
    int size() const { return m_size; }
    // Whether a launcher (mpirun, srun) started this process: MPI runs, even with one rank.
    bool launched() const { return m_active; }
    // This rank among the ranks on its node (MPI_COMM_TYPE_SHARED), and how many they are.
    int node_rank() const { return m_node_rank; }
    int node_size() const { return m_node_size; }
    // The bitwise or of every `bits` of the ranks on this node (all of them call it; one process:
    // bits): the CPUs of the node's masks together.
    std::vector<unsigned char> node_union(std::vector<unsigned char> bits) const;
    // Whether `ok` holds on every rank (all ranks call it; one process: ok).
    bool all(bool ok) const;
    // Rank 0's value, on every rank.
    std::size_t broadcast(std::size_t value) const;
    // The least of every rank's `value`, on every rank (all ranks call it; one process: value).
    std::size_t least(std::size_t value) const;
    // The lowest rank's non-empty `mine`, on rank 0 (all ranks call it; the others get ""; one
    // process: mine). For an error on another rank, which rank 0 alone reports.
    std::string first_message(const std::string& mine) const;
    // "MPI rank 3 on node07" (one process: "this process").
    std::string name() const;
    // The MPI window of the distribution's counter (MPI builds, more than one rank; else null):
    // allocated with the session, so that its cost is set-up, like MPI_Init's, not the run's.
    struct counter_window;
    counter_window* counter() const { return m_counter.get(); }
    struct node_group; // the node's ranks (their communicator)

  private:
    int m_rank = 0, m_size = 1, m_node_rank = 0, m_node_size = 1;
    bool m_active = false;
    std::unique_ptr<counter_window> m_counter;
    std::unique_ptr<node_group> m_node;
};

// The groups of `group` members (the last may be shorter) of members 0 .. count-1.
struct member_groups {
    std::size_t count, group;
    std::size_t size() const { return (count + group - 1) / group; }
    std::size_t first(std::size_t g) const { return g * group; }
    std::size_t members(std::size_t g) const { return std::min(group, count - g * group); }
    std::size_t end(std::size_t g) const { return std::min(count, g * group); } // before group g
};

// Work on members first .. first+count-1 (a group of neighbours; count 1 without lanes).
using batch_work = std::function<std::vector<member_outcome>(std::size_t first, std::size_t count)>;

// Runs members 0 .. count-1, in groups of `group` neighbours (the last may be shorter), on every
// rank's `jobs` threads. On rank 0 every outcome goes through `out` (in member order, to its sink),
// which bounds what waits in memory; progress(done) is called about ten times a second. Returns,
// on rank 0, what each rank did (rank order: its members, busy time, its first member's start and
// last member's end, from `start` on each rank); other ranks return nothing and may pass a null
// `out`.
std::vector<rank_work> run_distributed(const mpi_session& session, std::size_t count,
                                       std::size_t group, unsigned jobs, const batch_work& work,
                                       in_order* out,
                                       const std::function<void(std::size_t)>& progress,
                                       work_clock::time_point start);

// run_distributed on this process alone: every member on its `jobs` threads (returns one entry).
std::vector<rank_work> run_in_process(std::size_t count, std::size_t group, unsigned jobs,
                                      const batch_work& work, in_order& out,
                                      const std::function<void(std::size_t)>& progress,
                                      work_clock::time_point start);

// The bytes of outcomes (with their member indices) for a message, and back.
std::string pack(const std::vector<std::pair<std::size_t, member_outcome>>& outcomes);
std::vector<std::pair<std::size_t, member_outcome>> unpack(const std::string& bytes);

} // namespace rotgen
