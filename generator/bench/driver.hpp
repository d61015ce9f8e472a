// rotgen bench: the work-precision driver — its source (bench/workprecision/driver.cpp.in filled
// with every variant's kernels), compiled once (-O3, cached by a hash of the source, the harness,
// the runtime, the compiler and the flags), run on plan.txt, and its output (raw.txt) read.
#pragma once

#include "bench/bench.hpp"
#include "bench/initial_state.hpp"
#include "bench/sources.hpp"
#include "bench/variants.hpp"

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace rotgen::bench {

// The driver's source: every variant emitted (each variant's `header` is set here), its struct,
// and the template filled with them.
std::string driver_source(std::vector<variant>& variants, const scene_spec& scene,
                          const model_spec& spec, const derivation& d, const kinematics& k0,
                          const bench_options& opt, const bench_sources& src);

// `text` with each @name@ whose name is in `fills` replaced by its value; other @ left as they
// are.

struct compiled_driver {
    std::filesystem::path cache, exe; // the cache directory, and the driver in it
    std::string flags;                // the compiler flags (for the report)
    bool cached = false;              // found in the cache, not compiled
    double seconds = 0;               // wall time of compile_driver
};

// <cache_directory()>/bench, created; throws the user_error "DIR: cannot create the cache
// directory: REASON". `rotgen bench` calls it before it makes its output directory, so that a
// cache it cannot use leaves nothing behind.
std::filesystem::path bench_cache_root();

// The driver compiled (and cached in <cache_directory()>/bench/<scene_name>-<key>, with its
// driver.cpp) unless the cache has it; prints a line while compiling. Throws std::runtime_error
// with the compiler's output.
compiled_driver compile_driver(const std::string& source, const bench_sources& src,
                               const std::string& scene_name, std::size_t variant_count);

struct driver_run {
    std::filesystem::path raw;           // the driver's output
    double seconds = 0;                  // wall time of the sweep
    std::string load_before, load_after; // 1-min load average around it
};

// `exe dir/plan.txt dir/raw.txt`, with a progress line; throws std::runtime_error if it fails.
driver_run run_driver(const std::filesystem::path& exe, const std::filesystem::path& dir,
                      std::size_t configurations);

// One configuration's line of raw.txt.
struct result_row {
    std::size_t variant = 0;
    std::string peer, method, form, scalar, status;
    double tol = 0, step = 0, error = NAN, orientation = NAN;
    std::size_t rhs = 0, jac = 0, steps = 0;
    double median = NAN, min = NAN, max = NAN, energy_drift = NAN, momentum_drift = NAN;
    std::vector<std::string> y;
    bool at_floor = false; // error <= floor_factor x the reference's floor (read_output)
    // a run the tables, plots and choices rank: it ran, and its error is not the reference's own
    bool ok() const { return status == "ok" && std::isfinite(error) && !at_floor; }
};

// One sample of a long run.
struct drift_point {
    std::string label;
    double t, e;
    std::size_t steps, rhs;
};

struct driver_output {
    std::string compared; // the quantities the error is measured on
    std::string reference_source;
    double reference_error = NAN, reference_orientation = NAN;
    std::vector<std::string> reference_runs;
    std::vector<result_row> rows;
    std::vector<drift_point> drift_points;
    std::map<std::string, std::string> drift_failed; // long run label -> why
};

// raw.txt read (rows at the reference's floor marked at_floor); throws std::runtime_error if it
// has no result rows.
driver_output read_output(const std::filesystem::path& raw);

} // namespace rotgen::bench
