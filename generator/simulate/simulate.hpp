// rotgen simulate — integrate one scene (the run engine, run/engine.hpp) and write what it
// recorded: a CSV with the header `t,<recorded columns>`, an optional plot, and a summary on
// standard output (model, form, chart switch, method, steps, time, invariant drifts, events,
// files); a scene with `events:` also gets `<output stem>.events.csv` (header `event,t,<recorded
// columns>`, one row per event in time order).
#pragma once

#include <functional>
#include <string>

namespace rotgen {

struct scene_spec;

struct simulate_request {
    std::string scene;        // the scene file
    std::string csv;          // where to write the samples; empty: not written
    std::string plot;         // a PNG of the recorded columns; empty: none
    std::string events;       // the scene's events as CSV; empty: <output stem>.events.csv
    std::string view;         // a self-contained HTML page playing the run in 3D; empty: none
    std::string plot_axis;    // the figure axis on the unit sphere (simulate/figures.hpp)
    std::string plot_polhode; // the polhode of the body angular momentum
    bool timings = false;     // one line per pipeline stage to stderr
    bool quiet = false;       // no summary and no progress line
    std::string from;         // continue from the last row of this CSV (run/continue_from.hpp)
    // Resolves `method: auto` before the run (the CLI and Python pass tune/'s resolve_auto, a
    // later stage); unset: a scene with method auto is refused by the engine.
    std::function<void(scene_spec&)> resolve;
};

// Returns the exit status. Throws user_error for bad input (nothing is written then).
int simulate(const simulate_request& request);

} // namespace rotgen
