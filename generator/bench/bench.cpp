// rotgen bench SCENE.yaml [-o DIR] [--quick] [--long-steps N]
//
// The speed-accuracy trade of one scene, measured (DESIGN.md "Measuring the speed-accuracy
// trade"): derive -> emit every variant of the scene's equations (formulation x code generation,
// variants.hpp) -> fill bench/workprecision/driver.cpp.in -> compile it once (-O3, cached by a
// hash of the source, the harness, the runtime, the compiler and the flags; driver.hpp) -> run
// the driver on a plan of configurations (integrator x tolerance or step x scalar type x variant,
// and the peers Boost.Odeint and SUNDIALS CVODE on the same kernels; plan.hpp) -> results.csv,
// results.md, final_states.csv, drift.csv (report_tables.cpp) and the plots
// work_precision_time.png, work_precision_evals.png, invariant_drift.png (report_plots.cpp) in
// DIR (default bench-out/<scene>).
#include "bench/bench.hpp"

#include "bench/bench_internal.hpp"
#include "bench/files.hpp"
#include "bench/numbers.hpp"
#include "bench/sampled_error.hpp"
#include "expr/symbols.hpp"
#include "run/angle_chart.hpp"
#include "run/engine.hpp"
#include "run/kinematics.hpp"
#include "support/error.hpp"
#include "support/format.hpp"
#include "support/output_paths.hpp"

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iostream>

namespace rotgen {

namespace bench {

namespace {

namespace fs = std::filesystem;
using clock_type = std::chrono::steady_clock;

double seconds_since(clock_type::time_point t) {
    return std::chrono::duration<double>(clock_type::now() - t).count();
}

// The output directory, created, and refused unless writable.
void make_output_directory(const fs::path& dir) {
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
        throw user_error({dir.string()}, "the output path exists and is not a directory");
    fs::create_directories(dir, ec);
    if (ec) throw user_error({dir.string()}, "cannot create the output directory: " + ec.message());
    const fs::path probe = dir / (".probe" + std::to_string(::getpid()));
    std::ofstream p(probe);
    if (!p) throw user_error({dir.string()}, std::string("cannot write: ") + std::strerror(errno));
    p.close();
    fs::remove(probe, ec);
}

// Every file a bench run writes into its folder (the tables, the plots, their scripts and data).
const char* const bench_files[] = {"plan.txt",
                                   "raw.txt",
                                   "results.csv",
                                   "final_states.csv",
                                   "drift.csv",
                                   "results.md",
                                   "plot_data.dat",
                                   "drift_data.dat",
                                   "work_precision_time.png",
                                   "work_precision_time.png.gp",
                                   "work_precision_evals.png",
                                   "work_precision_evals.png.gp",
                                   "invariant_drift.png",
                                   "invariant_drift.gp"};

// None of them may be the scene or the model (refused before any work).
void check_files(const fs::path& dir, const scene_spec& scene) {
    std::vector<named_file> outputs;
    for (const char* f : bench_files)
        outputs.push_back({(dir / f).string(), "-o " + dir.string() + " (" + f + ")"});
    check_distinct_files(outputs, {{scene.file, "the scene"}, {scene.model.file, "the model"}});
}

// One `rotgen bench` run: its state (bench_context), and the stages, in the order run() calls
// them, that fill it.
class bench_run {
  public:
    int run(const bench_options& options) {
        m_wall0 = clock_type::now();
        stage_timings& t = m_ctx.timings;
        prepare(options);  // scene, sources, cache
        choose_variants(); // derive; the forms and code-generation variants
        // after every check of the input (the scene's form too): a refused run leaves nothing
        make_output_directory(m_ctx.dir);
        plan();
        write_file(m_ctx.dir / "plan.txt", m_ctx.plan.text); // the configurations -> plan.txt
        m_ctx.source = t.time("emit", "every variant (lowered and printed)", [&] {
            return driver_source(m_ctx.variants.variants, m_ctx.scene, m_ctx.spec, m_ctx.d,
                                 m_ctx.k0, m_ctx.opt, m_ctx.src); // emit every variant
        });
        m_ctx.generate_seconds = seconds_since(m_t_gen);
        m_ctx.driver = t.time("compile", "the driver", [&] {
            return compile_driver(m_ctx.source, m_ctx.src, m_ctx.scene_name,
                                  m_ctx.variants.variants.size()); // once per source, cached
        });
        m_ctx.run = t.time("integrate", "every configuration", [&] {
            return run_driver(m_ctx.driver.exe, m_ctx.dir, m_ctx.plan.lines); // -> raw.txt
        });
        m_ctx.output = read_output(m_ctx.run.raw);
        write_tables(m_ctx);                          // results.csv, final_states.csv, drift.csv
        m_ctx.summary = summarise(m_ctx.output.rows); // the best configuration per accuracy
        t.time("verify", "the chosen scenes", [&] { choose(); }); // in scene terms, run once
        std::string markdown = write_markdown(m_ctx, seconds_since(m_wall0));
        t.time("plot", "", [&] { draw_plots(m_ctx); });
        finish(markdown); // results.md, the summary on stdout
        if (m_ctx.opt.timings) t.print(std::cerr);
        return 0;
    }

    // The plan alone (plan.txt's text): nothing written, nothing compiled.
    std::string plan_only(const bench_options& options) {
        prepare(options);
        choose_variants();
        plan();
        return m_ctx.plan.text;
    }

  private:
    void prepare(const bench_options& options);
    void plan() {
        m_ctx.plan = make_plan(m_ctx.scene, m_ctx.spec, m_ctx.parameter_values, m_ctx.k0, m_ctx.opt,
                               m_ctx.conservative, m_ctx.variants, m_ctx.extra);
    }
    void choose_variants();
    void choose();
    void finish(std::string& markdown);
    void print_summary(double wall_seconds) const;

    bench_context m_ctx;
    clock_type::time_point m_wall0, m_t_gen;
};

void bench_run::prepare(const bench_options& options) {
    bench_context& c = m_ctx;
    c.opt = options;
    c.scene = load_scene(c.opt.scene, "bench");
    if (c.scene.t_end < c.scene.t_start) // its references and plans are for forward runs
        throw user_error(c.scene.time_where, "bench measures forward runs: time end must be "
                                             "after time start (simulate runs backward)");
    if (c.scene.model.rotor)
        throw user_error(c.scene.model.rotor_where,
                         "model '" + c.scene.model.name +
                             "' is a linear rotor (a body on a line, Example 5.4): bench compares "
                             "the three-angle forms and their peers (Boost.Odeint, CVODE) on "
                             "them, and a rotor has one form of two angles, rotor; run it with "
                             "'rotgen simulate' or 'rotgen sweep'");
    c.spec = c.scene.model; // with the scene's parameter values
    for (std::size_t i = 0; i < c.spec.parameters.size(); ++i)
        c.spec.parameters[i].value = c.scene.parameters[i];
    c.src = find_bench_sources();
    c.dir = c.opt.dir;
    check_files(c.dir, c.scene);
    const angle_convention& angles = c.scene.model.angles;
    c.euler_ok = chart_distance(sequence_of(angles), c.scene.angles[1]) > 1e-10;
    if (!c.euler_ok && c.scene.form != form_kind::body)
        throw user_error(c.scene.initial_where,
                         "initial " + angles.names[1] +
                             " is the gimbal-lock singularity of the Euler-angle forms (" +
                             distance_words(angles) + " = 0); use form: body");
    bench_cache_root(); // a cache that cannot be made is refused before any output
}

void bench_run::choose_variants() {
    bench_context& c = m_ctx;
    m_t_gen = clock_type::now();
    c.d = c.timings.time("derive", c.spec.name, [&] { return derive(c.spec); });
    for (std::size_t i = 0; i < c.spec.parameters.size(); ++i)
        c.parameter_values[c.spec.parameters[i].symbol] =
            exact_scene_value(c.scene.parameters[i], c.scene.parameters_written[i]);
    c.k0 = initial_kinematics_of(c.scene, c.d);
    check_double_range(c.scene, c.k0);
    c.conservative = !c.spec.has_damping && !c.spec.has_torque;
    c.scene_name = fs::path(c.opt.scene).stem().string();
    check_split(c.scene, c.parameter_values, c.extra); // the checks simulate makes
    c.variants = c.timings.time("forms", "every variant", [&] {
        return bench::choose_variants(c.scene, c.spec, c.d, c.euler_ok && c.k0.have_rates,
                                      needs_orientation(c.scene, false), c.opt.quick,
                                      !c.extra.split_refusal);
    });
    check_taylor(c.spec, c.variants.variants[0], c.extra);
}

// The choice per level in scene terms, each scene run through the engine and measured against the
// tight reference of the one error measure (levels below 3x that reference's floor are not
// verifiable and get no choice).
void bench_run::choose() {
    bench_context& c = m_ctx;
    const reference_run ref = make_reference(c.scene);
    c.verify_floor = ref.floor;
    const verify_fn verify = [&](const scene_spec& s) {
        const measured_run m = measure_scene(scene_for_error(s), &ref.result, 1);
        return m.ok ? m.error : NAN;
    };
    std::vector<double> levels;
    for (const double l : c.summary.levels)
        if (l > floor_factor * ref.floor) levels.push_back(l);
    c.choices = choose_scenes(c.output.rows, c.variants.variants, c.scene, levels,
                              c.output.reference_error, verify);
}

void bench_run::finish(std::string& markdown) {
    const double wall_seconds = seconds_since(m_wall0);
    markdown +=
        "\nWall time of the whole `rotgen bench` run: " + short_number(wall_seconds) + " s.\n";
    write_file(m_ctx.dir / "results.md", markdown);
    print_summary(wall_seconds);
}

void bench_run::print_summary(double wall_seconds) const {
    const bench_context& c = m_ctx;
    const driver_output& out = c.output;
    std::size_t failed = 0;
    for (const auto& r : out.rows)
        failed += r.status != "ok";
    std::cout << "rotgen bench " << c.opt.scene << "\n"
              << "  variants  ";
    for (std::size_t i = 0; i < c.variants.variants.size(); ++i)
        std::cout << (i ? ", " : "") << c.variants.variants[i].label;
    std::cout << "\n  reference " << out.reference_source << " (floor "
              << short_number(out.reference_error) << ")\n  compared  " << out.compared << "\n"
              << "  runs      " << out.rows.size() << " configurations (" << failed << " failed), "
              << c.plan.drift_labels.size() << " long runs\n"
              << "  time      " << format_duration(c.generate_seconds) << " generating, "
              << (c.driver.cached ? std::string("cached driver")
                                  : format_duration(c.driver.seconds) + " compiling")
              << ", " << format_duration(c.run.seconds) << " sweeping, "
              << format_duration(wall_seconds) << " in all\n"
              << "  harness   " << c.src.harness.string() << ", runtime " << c.src.runtime.string()
              << "\n";
    for (const auto& why : c.plan.left_out)
        std::cout << "  left out  " << why << "\n";
    std::cout << choices_text(c, "  ");
    std::cout << "  wrote     " << (c.dir / "results.csv").string()
              << ", results.md, final_states.csv, "
              << "drift.csv, work_precision_time.png, work_precision_evals.png"
              << (c.plan.drift_labels.empty() ? "" : ", invariant_drift.png") << "\n";
}

} // namespace

} // namespace bench

int run_bench(const bench_options& options) {
    return bench::bench_run().run(options);
}

std::string bench_plan_text(const bench_options& options) {
    return bench::bench_run().plan_only(options);
}

} // namespace rotgen
