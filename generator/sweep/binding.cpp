#include "sweep/binding.hpp"

#include "support/error.hpp"
#include "sweep/parallel.hpp"

#ifdef __linux__
#include <sched.h>
#include <unistd.h>
#endif

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace rotgen {

binding_policy binding_of_environment() {
    const char* v = std::getenv("ROTGEN_BINDING");
    const std::string policy = v ? v : "";
    if (policy.empty() || policy == "auto") return binding_policy::automatic;
    if (policy == "keep") return binding_policy::keep;
    throw user_error({"ROTGEN_BINDING=" + policy},
                     "unknown binding policy; use keep (the launcher's binding) or auto (the "
                     "default: threads that outnumber a rank's cores get cores of their own)");
}

std::vector<int> cpu_list(const std::string& text) {
    std::vector<int> cpus;
    std::istringstream in(text);
    for (std::string range; std::getline(in, range, ',');) {
        int first = 0, last = 0;
        char dash = 0;
        std::istringstream r(range);
        if (!(r >> first)) return {};
        last = first;
        if (r >> dash && (dash != '-' || !(r >> last))) return {};
        if (last < first || last - first > 65536) return {};
        for (int c = first; c <= last; ++c)
            cpus.push_back(c);
    }
    return cpus;
}

std::vector<int> cpus_for_rank(const std::vector<core_cpus>& cores, unsigned jobs, int node_rank,
                               int node_size) {
    std::vector<int> cpus;
    const bool fit = node_rank >= 0 && std::size_t(node_size) * jobs <= cores.size();
    const std::size_t first = fit ? std::size_t(node_rank) * jobs : 0;
    const std::size_t end = fit ? first + jobs : cores.size();
    for (std::size_t k = first; k < end; ++k)
        cpus.insert(cpus.end(), cores[k].begin(), cores[k].end());
    std::sort(cpus.begin(), cpus.end());
    return cpus;
}

std::size_t cpus_in(const std::vector<unsigned char>& mask) {
    std::size_t n = 0;
    for (unsigned char byte : mask)
        for (; byte != 0; byte &= static_cast<unsigned char>(byte - 1))
            ++n;
    return n;
}

#ifdef __linux__

std::vector<unsigned char> cpu_mask() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0) return {};
    const auto* bytes = reinterpret_cast<const unsigned char*>(&set);
    return {bytes, bytes + sizeof set};
}

namespace {

std::vector<int> affinity(pid_t process = 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    std::vector<int> cpus;
    if (sched_getaffinity(process, sizeof set, &set) != 0) return cpus;
    for (int c = 0; c < CPU_SETSIZE; ++c)
        if (CPU_ISSET(c, &set)) cpus.push_back(c);
    return cpus;
}

bool bind_to(const std::vector<int>& cpus) {
    cpu_set_t set;
    CPU_ZERO(&set);
    for (const int c : cpus)
        CPU_SET(c, &set);
    return sched_setaffinity(0, sizeof set, &set) == 0;
}

// The cores this process may be bound to: those its launcher (the parent: mpirun, orted,
// slurmstepd) may run on, less those the cpuset withholds (asked for every core, the kernel grants
// those the cpuset allows). A launcher held by taskset keeps its ranks to its cores.
std::vector<int> allowed_cores() {
    std::vector<int> every(CPU_SETSIZE);
    for (int c = 0; c < CPU_SETSIZE; ++c)
        every[std::size_t(c)] = c;
    const std::vector<int> launcher = affinity(getppid());
    if (!bind_to(launcher.empty() ? every : launcher)) return {};
    return affinity();
}

// The CPUs that share CPU c's core (sysfs); {c} where that is unknown.
std::vector<int> siblings_of(int c) {
    std::ifstream in("/sys/devices/system/cpu/cpu" + std::to_string(c) +
                     "/topology/thread_siblings_list");
    std::string line;
    std::vector<int> list = std::getline(in, line) ? cpu_list(line) : std::vector<int>{};
    return list.empty() ? std::vector<int>{c} : list;
}

} // namespace

thread_cores place_threads(unsigned jobs, bool launched, int node_rank, int node_size,
                           binding_policy policy) {
    const std::vector<int> bound = affinity();
    thread_cores placed{bound.size(), bound.size(), false, false};
    if (bound.empty() || jobs <= bound.size() || !launched || policy == binding_policy::keep)
        return placed;
    const std::vector<int> allowed = allowed_cores();
    if (allowed.size() <= bound.size()) { // nothing gained: back to the launcher's binding
        bind_to(bound);
        return placed;
    }
    const std::vector<int> mine =
        cpus_for_rank(group_by_core(allowed, siblings_of), jobs, node_rank, node_size);
    if (!bind_to(mine)) {
        bind_to(bound);
        return placed;
    }
    placed.cores = affinity().size(); // what the kernel granted
    placed.rebound = true;
    placed.shared = mine.size() == allowed.size() && node_size > 1;
    return placed;
}

#else

std::vector<unsigned char> cpu_mask() {
    std::vector<unsigned char> mask((all_cores() + 7) / 8);
    for (std::size_t c = 0; c < all_cores(); ++c)
        mask[c / 8] |= static_cast<unsigned char>(1u << (c % 8));
    return mask;
}

thread_cores place_threads(unsigned, bool, int, int, binding_policy) {
    const std::size_t n = all_cores();
    return {n, n, false, false};
}

#endif

} // namespace rotgen
