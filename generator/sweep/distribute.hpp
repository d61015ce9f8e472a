// rotgen sweep across processes — under `mpirun -n R rotgen sweep ...` (built with ROTGEN_MPI) the
// members are shared by R ranks through a dynamic work queue held by rank 0: a rank asks for a
// chunk of member indices, runs it on its threads, sends the outcomes back and asks again (chunks
// shrink as the queue empties: remaining / (4 ranks), at least 1, so that the last members do not
// wait behind a long chunk). Rank 0 runs members on its own threads too, and its main thread
// answers the other ranks (MPI called from that thread only: MPI_THREAD_FUNNELED). Every outcome
// goes through rank 0's window, which alone writes the files: they are the same byte for
// byte as a one-process run's. Started without mpirun (or built without MPI) it is one process.
#pragma once

#include "sweep/in_order.hpp"
#include "sweep/outcome.hpp"

#include <functional>
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
    // Whether `ok` holds on every rank (all ranks call it; one process: ok).
    bool all(bool ok) const;
    // Rank 0's value, on every rank.
    std::size_t broadcast(std::size_t value) const;
    // The least of every rank's `value`, on every rank (all ranks call it; one process: value).
    std::size_t least(std::size_t value) const;

  private:
    int m_rank = 0, m_size = 1;
    bool m_active = false;
};

// Work on members first .. first+count-1 (a group of neighbours; count 1 without lanes).
using batch_work = std::function<std::vector<member_outcome>(std::size_t first, std::size_t count)>;

// Runs members 0 .. count-1, in groups of `group` neighbours (the last may be shorter), on every
// rank's `jobs` threads. On rank 0 every outcome goes through `out` (in member order, to its sink),
// which bounds what waits in memory; progress(done) is called about ten times a second. Returns,
// on rank 0, how many members each rank ran (rank order); other ranks return nothing and may pass
// a null `out`.
std::vector<std::size_t> run_distributed(const mpi_session& session, std::size_t count,
                                         std::size_t group, unsigned jobs, const batch_work& work,
                                         in_order* out,
                                         const std::function<void(std::size_t)>& progress);

// The bytes of outcomes (with their member indices) for a message, and back.
std::string pack(const std::vector<std::pair<std::size_t, member_outcome>>& outcomes);
std::vector<std::pair<std::size_t, member_outcome>> unpack(const std::string& bytes);

} // namespace rotgen
