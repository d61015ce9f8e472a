// rotgen bench — timing the configurations: for each, the median, min and max of `repeats`
// measurements, each the mean over a loop of whole integrations that lasts at least `target`
// seconds.
//
//   calibration  per configuration, the loop length doubles from one integration until a batch
//                takes >= target/10 (this also warms caches and branch predictors), then
//                loops = ceil(target / (batch time / batch size));
//   measurement  in `repeats` rounds, each round timing every configuration's loop once
//                (round-robin): other processes on a shared machine come in bursts, and a burst
//                then spoils one sample of many configurations instead of all samples of one.
// Every integration restarts from the initial state; its result feeds a volatile sink so that the
// compiler cannot drop the work.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

namespace rotgen::bench {

struct timing {
    double median = NAN, min = NAN, max = NAN;
    long loops = 0;
};

inline volatile double timing_sink = 0;

// A configuration ready to be timed: one call of `once` integrates once from the initial state.
struct timed_job {
    std::function<double()> once; // empty: nothing to time (the run failed)
    long loops = 0;
    std::vector<double> samples; // seconds per integration, one per round
};

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

inline void calibrate(timed_job& job, double target) {
    if (!job.once) return;
    long batch = 1;
    for (;;) {
        const auto t0 = std::chrono::steady_clock::now();
        double s = 0;
        for (long i = 0; i < batch; ++i)
            s += job.once();
        timing_sink = timing_sink + s;
        const double dt = seconds_since(t0);
        if (dt >= target / 10 || batch >= (1L << 30)) {
            const double per_run = dt / double(batch);
            job.loops =
                std::max(1L, static_cast<long>(std::ceil(target / std::max(per_run, 1e-12))));
            return;
        }
        batch *= 2;
    }
}

inline void sample(timed_job& job) {
    if (!job.once) return;
    const auto t0 = std::chrono::steady_clock::now();
    double s = 0;
    for (long i = 0; i < job.loops; ++i)
        s += job.once();
    timing_sink = timing_sink + s;
    job.samples.push_back(seconds_since(t0) / double(job.loops));
}

inline timing summary(const timed_job& job) {
    timing t;
    t.loops = job.loops;
    if (job.samples.empty()) return t;
    std::vector<double> v = job.samples;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    t.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    t.min = v.front();
    t.max = v.back();
    return t;
}

} // namespace rotgen::bench
