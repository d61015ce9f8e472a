// rotgen sweep — members on threads: a fixed pool takes member indices from a shared source, one
// at a time, until it is exhausted (a dynamic queue: members differ in cost). Each member's
// result goes to its own slot, so the outputs do not depend on the number of threads or on the
// order in which members finish.
#pragma once

#include <cstddef>
#include <functional>

namespace rotgen {

// The number of threads a sweep runs without -j (one process): every core this process may run on
// (its CPU affinity, which taskset, Slurm's cpusets and mpirun's binding restrict;
// std::thread::hardware_concurrency where the affinity is unknown), at least 1.
unsigned all_cores();

// Calls work(m) for every index next() gives until it gives `none`, on `jobs` threads (jobs 1: on
// the calling thread). next() and work() are called concurrently. While they run, the calling
// thread calls tick() about ten times a second (for a progress line; may be empty). The first
// exception a work() throws stops the pool (no new members) and is rethrown here.
constexpr std::size_t none = static_cast<std::size_t>(-1);
void run_pool(unsigned jobs, const std::function<std::size_t()>& next,
              const std::function<void(std::size_t)>& work, const std::function<void()>& tick);

} // namespace rotgen
