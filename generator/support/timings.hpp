// rotgen — wall time per pipeline stage, for `--timings` (one line per stage run, to stderr):
//
//   rotgen: timing derive    0.012 s
//   rotgen: timing forms     0.004 s  lagrangian
//   rotgen: timing compile   0.210 s  heavy_top (cached)
//
// Each stage is reported once each time it runs, so the lines also show that nothing is built
// twice.
#pragma once

#include "support/signals.hpp"

#include <chrono>
#include <ostream>
#include <string>
#include <vector>

namespace rotgen {

class stage_timings {
  public:
    struct entry {
        std::string stage, detail;
        double seconds;
    };

    // Runs `work()` as stage `stage` and records its wall time; returns what work() returns.
    template <class Work>
    auto time(const std::string& stage, const std::string& detail, Work&& work) {
        signal_test_hook(stage);
        const auto start = std::chrono::steady_clock::now();
        struct recorder { // records on the way out, also when work() throws
            stage_timings& t;
            const std::string &stage, &detail;
            std::chrono::steady_clock::time_point start;
            ~recorder() {
                t.m_entries.push_back(
                    {stage, detail,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                         .count()});
            }
        } r{*this, stage, detail, start};
        return work();
    }

    // Seconds spent in `stage`, over all its runs.
    double total(const std::string& stage) const;
    const std::vector<entry>& entries() const { return m_entries; }
    void print(std::ostream& os) const;

  private:
    std::vector<entry> m_entries;
};

} // namespace rotgen
