// rotgen sweep — an ensemble of runs of one scene (a parameter sweep or a Monte Carlo set), through
// the one run engine: the scene is prepared (derived, its kernels compiled) once, and every
// member runs on it with its own initial values and parameter values (sweep/members.hpp).
//
// Output in the directory DIR, each file written whole or not at all:
//   summary.csv       one row per member, in member order: member, the varied keys as written,
//                     final.t and final.<column> for every recorded column (the last sample
//                     reached), drift.<invariant> (max |v(t) - v(t0)| over the samples), steps
//                     (accepted), rhs_evals, status (ok, or why the run stopped); no timings, so
//                     the file is the same byte for byte on every run;
//   trajectories.h5   with --trajectories: every member's samples (sweep/trajectories.hpp).
// A member that fails does not stop the others; the exit status is then 3. Members run on `jobs`
// threads (sweep/parallel.hpp); the files are the same for every number of threads.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace rotgen {

struct scene_spec;

struct sweep_request {
    std::string scene;             // the scene file
    std::string directory;         // where the files go (created if missing)
    std::vector<std::string> vary; // --vary KEY=FROM:TO:COUNT entries
    unsigned jobs = 0;             // threads; 0: every core
    unsigned lanes = 1;            // > 1: members in SIMD batches of this many (run/lanes.hpp)
    bool trajectories = false;     // also DIR/trajectories.h5 (sweep/trajectories.hpp)
    bool timings = false;          // one line per pipeline stage to stderr
    bool quiet = false;            // no summary and no progress line
    bool resume = false;           // go on from DIR's journal (sweep/journal.hpp)
    // Resolves `method: auto` once for every member (the CLI passes tune/'s resolve_auto).
    std::function<void(scene_spec&)> resolve;
};

// Returns the exit status: 0, or 3 if a member failed. Throws user_error for bad input (nothing
// is written then).
int sweep(const sweep_request& request);

} // namespace rotgen
