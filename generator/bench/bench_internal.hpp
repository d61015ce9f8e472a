// rotgen bench: the state of one `rotgen bench` run, filled stage by stage by bench.cpp and read
// by the report writers (report_tables.cpp, report_plots.cpp).
#pragma once

#include "bench/bench.hpp"
#include "bench/driver.hpp"
#include "bench/initial_state.hpp"
#include "bench/plan.hpp"
#include "bench/scene_choice.hpp"
#include "bench/sources.hpp"
#include "bench/split_taylor.hpp"
#include "bench/summary.hpp"
#include "bench/variants.hpp"
#include "support/timings.hpp"

#include <filesystem>
#include <string>

namespace rotgen::bench {

struct bench_context {
    bench_options opt;
    stage_timings timings;
    scene_spec scene;
    model_spec spec; // the scene's model, with the scene's parameter values
    bench_sources src;
    std::filesystem::path dir; // the output directory
    std::string scene_name;    // the scene file's stem
    bool euler_ok = true;      // sin theta != 0 at the start
    bool conservative = true;  // no damping, no torque
    derivation d;
    GiNaC::exmap parameter_values;
    kinematics k0;
    variant_set variants;
    split_taylor_methods extra; // whether split2/4/6 and taylor run
    bench_plan plan;
    std::string source; // the driver's
    double generate_seconds = 0;
    compiled_driver driver;
    driver_run run;
    driver_output output;
    bench_summary summary; // points into output.rows
    // per level of summary.levels: the fastest scene simulate runs, verified (scene_choice.hpp);
    // the one choice the console and results.md print
    std::vector<scene_choice> choices;
    double verify_floor = 0; // the verification reference's floor (sampled_error.hpp)
};

// The choice at each level, in scene terms: what the console and results.md print (one text).
std::string choices_text(const bench_context& ctx, const std::string& indent);

// results.csv, final_states.csv, drift.csv in ctx.dir.
void write_tables(const bench_context& ctx);

// results.md but its last line (the wall time); `wall_seconds_so_far`: the run's time until now.
std::string write_markdown(const bench_context& ctx, double wall_seconds_so_far);

// work_precision_time.png, work_precision_evals.png and (with long runs) invariant_drift.png in
// ctx.dir, with their data and gnuplot scripts.
void draw_plots(const bench_context& ctx);

} // namespace rotgen::bench
