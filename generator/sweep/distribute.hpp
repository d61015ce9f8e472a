// rotgen sweep across processes — under `mpirun -n R rotgen sweep ...` (built with ROTGEN_MPI) the
// members are shared by R ranks through a dynamic work queue held by rank 0: a rank asks for a
// chunk of member indices, runs it on its threads, sends the outcomes back and asks again (chunks
// shrink as the queue empties: remaining / (4 ranks), at least 1, so that the last members do not
// wait behind a long chunk). Rank 0 runs members on its own threads too, and its main thread
// answers the other ranks (MPI called from that thread only: MPI_THREAD_FUNNELED). Every outcome
// goes to its member's slot on rank 0, which alone writes the files: they are the same byte for
// byte as a one-process run's. Started without mpirun (or built without MPI) it is one process.
#pragma once

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

  private:
    int m_rank = 0, m_size = 1;
    bool m_active = false;
};

using member_work = std::function<member_outcome(std::size_t member)>;

// Runs members 0 .. count-1 on every rank's `jobs` threads. Rank 0 returns every outcome in member
// order, having called progress(done) about ten times a second; other ranks return nothing.
std::vector<member_outcome> run_distributed(const mpi_session& session, std::size_t count,
                                            unsigned jobs, const member_work& work,
                                            const std::function<void(std::size_t)>& progress);

// The same for members run in groups of `group` neighbours (the last group may be shorter):
// work(first, n) gives the outcomes of members first .. first+n-1. Ranks take chunks of groups.
using batch_work = std::function<std::vector<member_outcome>(std::size_t first, std::size_t count)>;
std::vector<member_outcome> run_distributed(const mpi_session& session, std::size_t count,
                                            std::size_t group, unsigned jobs,
                                            const batch_work& work,
                                            const std::function<void(std::size_t)>& progress);

// The bytes of outcomes (with their member indices) for a message, and back.
std::string pack(const std::vector<std::pair<std::size_t, member_outcome>>& outcomes);
std::vector<std::pair<std::size_t, member_outcome>> unpack(const std::string& bytes);

} // namespace rotgen
