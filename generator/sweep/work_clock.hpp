// rotgen sweep — what a process's threads did in a run, for the summary's ranks line and the
// `--timings` balance lines: the members they ran, the time they spent in them together, and
// when the last one ended. A rank that idles while others work shows here as a busy share below
// its threads' and an early last member.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace rotgen {

// One process's (rank's) share of a run.
struct rank_work {
    std::size_t members = 0;    // members its threads ran
    double busy = 0;            // seconds its threads spent running members, summed over them
    double first = 0, last = 0; // seconds from the run's start to its first member's start and
                                // to its last member's end
};

// Times every call of a work function (`wrap`), from any thread, from `origin` (the run's start).
class work_clock {
  public:
    using time_point = std::chrono::steady_clock::time_point;
    explicit work_clock(time_point origin) : m_start(origin) {}
    // `work` timed: each call's members, duration and end are counted. `work` must outlive it.
    template <class Work> auto wrap(const Work& work) {
        return [this, &work](std::size_t first, std::size_t count) {
            const auto begin = std::chrono::steady_clock::now();
            auto outcome = work(first, count);
            const auto end = std::chrono::steady_clock::now();
            m_members += outcome.size();
            m_busy_ns += nanoseconds(end - begin);
            lower(m_first_ns, nanoseconds(begin - m_start));
            raise(m_last_ns, nanoseconds(end - m_start));
            return outcome;
        };
    }
    rank_work read() const {
        const std::uint64_t first = m_members ? m_first_ns.load() : 0;
        return {m_members, 1e-9 * double(m_busy_ns), 1e-9 * double(first),
                1e-9 * double(m_last_ns)};
    }

  private:
    static void lower(std::atomic<std::uint64_t>& a, std::uint64_t v) {
        for (std::uint64_t seen = a; v < seen;)
            if (a.compare_exchange_weak(seen, v)) break;
    }
    static void raise(std::atomic<std::uint64_t>& a, std::uint64_t v) {
        for (std::uint64_t seen = a; seen < v;)
            if (a.compare_exchange_weak(seen, v)) break;
    }
    static std::uint64_t nanoseconds(std::chrono::steady_clock::duration d) {
        return std::uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(d).count());
    }
    const time_point m_start;
    std::atomic<std::size_t> m_members{0};
    std::atomic<std::uint64_t> m_busy_ns{0}, m_first_ns{UINT64_MAX}, m_last_ns{0};
};

} // namespace rotgen
