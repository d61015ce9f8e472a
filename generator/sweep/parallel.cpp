#include "sweep/parallel.hpp"

#ifdef __linux__
#include <sched.h>
#endif

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace rotgen {

unsigned all_cores() {
#ifdef __linux__
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0)
        return static_cast<unsigned>(CPU_COUNT(&set));
#endif
    const unsigned n = std::thread::hardware_concurrency();
    return n == 0 ? 1 : n;
}

void run_pool(unsigned jobs, const std::function<std::size_t()>& next,
              const std::function<void(std::size_t)>& work, const std::function<void()>& tick) {
    std::mutex m;
    std::condition_variable finished;
    std::exception_ptr failure;
    std::atomic<bool> stop{false};
    unsigned running = jobs;
    const auto worker = [&] {
        try {
            for (std::size_t i; !stop && (i = next()) != none;)
                work(i);
        } catch (...) {
            const std::lock_guard<std::mutex> lock(m);
            if (!failure) failure = std::current_exception();
            stop = true;
        }
        const std::lock_guard<std::mutex> lock(m);
        --running;
        finished.notify_all();
    };
    if (jobs <= 1) { // the calling thread works, and ticks between members
        for (std::size_t i; (i = next()) != none;) {
            work(i);
            if (tick) tick();
        }
        return;
    }
    std::vector<std::thread> pool;
    for (unsigned j = 0; j < jobs; ++j)
        pool.emplace_back(worker);
    {
        std::unique_lock<std::mutex> lock(m);
        while (running > 0) {
            finished.wait_for(lock, std::chrono::milliseconds(100));
            if (tick) {
                lock.unlock();
                tick();
                lock.lock();
            }
        }
    }
    for (auto& t : pool)
        t.join();
    if (failure) std::rethrow_exception(failure);
}

} // namespace rotgen
