// rotgen sweep — the cores a rank's threads run on. An MPI launcher binds each rank to cores of
// its choosing: Open MPI 4 binds to one core when it starts 2 ranks or fewer (to a socket above
// that), so `mpirun -n 2 rotgen sweep -j 8` would run each rank's 8 threads on one core, 8 times
// slower than the same cores as threads. Under a launcher, when a rank's threads outnumber the
// cores it is bound to, rotgen binds it again, before its threads start:
// - to `jobs` cores of its own when the cores its node allows hold every rank's threads: rank k
//   of the node gets the allowed cores k*jobs .. k*jobs+jobs-1, each with its hardware threads,
//   as `--map-by slot:PE=jobs` would.
//   The allowed cores are those the launcher itself (the parent process: mpirun, orted,
//   slurmstepd) may run on, less those a batch system's cpuset withholds (the kernel keeps that);
// - else to all of the allowed cores, which the node's ranks then share.
// ROTGEN_BINDING=keep keeps the launcher's binding (the summary then warns); auto (or unset) is
// the default. A process started without a launcher keeps its affinity (taskset's, for one).
#pragma once

#include <algorithm>
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

// A core: the allowed CPUs (hardware threads) that share it, ascending.
using core_cpus = std::vector<int>;

// The CPUs of a list in the kernel's format ("0-3,8,10-11"); empty if it is not one.
std::vector<int> cpu_list(const std::string& text);

// The allowed CPUs (ascending) grouped by core, in the order of their first CPU; `siblings(c)` is
// the CPUs that share c's core (sysfs' thread_siblings_list; {c} where it is unknown).
template <class Siblings>
std::vector<core_cpus> group_by_core(const std::vector<int>& allowed, Siblings siblings);

// The CPUs that node rank `node_rank` of `node_size` ranks of `jobs` threads each takes: `jobs`
// cores of its own (rank k: cores k*jobs .. k*jobs+jobs-1, with all their hardware threads) when
// every rank's threads fit the cores, else every allowed CPU.
std::vector<int> cpus_for_rank(const std::vector<core_cpus>& cores, unsigned jobs, int node_rank,
                               int node_size);

// The CPUs this process may run on now, as bits (the bytes of its affinity mask; elsewhere than
// Linux, as many bits as it has cores), and how many bits are set in such a mask: a node's ranks
// or their masks together (mpi_session::node_union) for the cores the node's ranks run on.
std::vector<unsigned char> cpu_mask();
std::size_t cpus_in(const std::vector<unsigned char>& mask);

// Binds this process (as above) when `launched` by MPI, the policy is automatic and `jobs`
// outnumbers its cores; call it before any worker thread starts (threads inherit the binding).
thread_cores place_threads(unsigned jobs, bool launched, int node_rank, int node_size,
                           binding_policy policy);

template <class Siblings>
std::vector<core_cpus> group_by_core(const std::vector<int>& allowed, Siblings siblings) {
    std::vector<core_cpus> cores;
    std::vector<int> placed;
    for (const int c : allowed) {
        if (std::find(placed.begin(), placed.end(), c) != placed.end()) continue;
        core_cpus core{c};
        for (const int s : siblings(c))
            if (s != c && std::binary_search(allowed.begin(), allowed.end(), s)) core.push_back(s);
        std::sort(core.begin(), core.end());
        placed.insert(placed.end(), core.begin(), core.end());
        cores.push_back(std::move(core));
    }
    return cores;
}

} // namespace rotgen
