// rotgen sweep — the cores a rank's threads run on. An MPI launcher binds each rank to cores of
// its choosing: Open MPI 4 binds to one core when it starts 2 ranks or fewer (to a socket above
// that), so `mpirun -n 2 rotgen sweep -j 8` would run each rank's 8 threads on one core, 8 times
// slower than the same cores as threads. Under a launcher, when a rank's threads outnumber the
// cores it is bound to, rotgen binds it again, before its threads start:
// - to `jobs` cores of its own when the cores its node allows hold every rank's threads: rank k
//   of the node gets the allowed cores k*jobs .. k*jobs+jobs-1, as `--map-by slot:PE=jobs` would.
//   The allowed cores are those the launcher itself (the parent process: mpirun, orted,
//   slurmstepd) may run on, less those a batch system's cpuset withholds (the kernel keeps that);
// - else to all of the allowed cores, which the node's ranks then share.
// ROTGEN_BINDING=keep keeps the launcher's binding (the summary then warns); auto (or unset) is
// the default. A process started without a launcher keeps its affinity (taskset's, for one).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace rotgen {

enum class binding_policy { automatic, keep };

// ROTGEN_BINDING's policy; user_error for a value other than auto or keep.
binding_policy binding_of_environment();

struct thread_cores {
    std::size_t bound = 0; // the cores the process was bound to
    std::size_t cores = 0; // the cores its threads run on
    bool rebound = false;  // rotgen changed its binding
    bool shared = false;   // ... to all of the node's allowed cores, shared with its other ranks
};

// The allowed cores `cpus` (ascending) that node rank `node_rank` of `node_size` ranks of `jobs`
// threads each takes: its own block when all blocks fit, else all of them.
std::vector<int> cores_for_rank(const std::vector<int>& allowed, unsigned jobs, int node_rank,
                                int node_size);

// Binds this process (as above) when `launched` by MPI, the policy is automatic and `jobs`
// outnumbers its cores; call it before any worker thread starts (threads inherit the binding).
thread_cores place_threads(unsigned jobs, bool launched, int node_rank, int node_size,
                           binding_policy policy);

} // namespace rotgen
