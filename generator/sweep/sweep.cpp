#include "sweep/sweep.hpp"

#include "run/lanes.hpp"
#include "run/prepared.hpp"
#include "scene/scene.hpp"
#include "support/atomic_file.hpp"
#include "support/error.hpp"
#include "support/format.hpp"
#include "support/output_paths.hpp"
#include "support/progress.hpp"
#include "support/timings.hpp"
#include "sweep/distribute.hpp"
#include "sweep/members.hpp"
#include "sweep/outcome.hpp"
#include "sweep/parallel.hpp"
#include "sweep/trajectories.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>
#include <sstream>

namespace rotgen {

namespace {

// DIR, created if missing (not its parents); user_error if it cannot be, or is not a directory.
void make_directory(const std::string& dir) {
    if (dir.empty() || dir == "-")
        throw user_error({"rotgen sweep"}, "-o needs a directory (the sweep writes several files)");
    struct stat st {};
    if (::stat(dir.c_str(), &st) == 0) {
        if (!S_ISDIR(st.st_mode)) throw user_error({dir}, "not a directory");
        return;
    }
    if (::mkdir(dir.c_str(), 0755) != 0)
        throw user_error({dir},
                         std::string("cannot create the directory: ") + std::strerror(errno));
}

// The files the sweep writes into DIR, none of them one of its inputs (refused before any work).
void check_files(const sweep_request& q, const scene_spec& scene) {
    std::vector<named_file> outputs{{q.directory + "/summary.csv", "-o " + q.directory}};
    if (q.trajectories) outputs.push_back({q.directory + "/trajectories.h5", "--trajectories"});
    check_distinct_files(outputs, {{q.scene, "the scene"}, {scene.model.file, "the model"}});
}

std::string mode_name(sweep_mode m) {
    return m == sweep_mode::grid ? "grid" : m == sweep_mode::zip ? "zip" : "random";
}

// `lanes` the batch kernel's target with --lanes W > 1, else empty.
void print_summary(std::ostream& os, const sweep_request& q, const scene_spec& scene,
                   const sweep_plan& plan, const std::vector<member_outcome>& outcomes,
                   const std::string& workers, const std::string& lanes, double seconds) {
    std::uint64_t steps = 0, evals = 0;
    std::size_t failed = 0, in_lanes = 0;
    for (const auto& o : outcomes) {
        steps += o.steps, evals += o.rhs_evals;
        failed += o.ok() ? 0 : 1;
        in_lanes += o.in_lanes ? 1 : 0;
    }
    std::string keys;
    for (const auto& k : plan.keys)
        keys += (keys.empty() ? "" : ", ") + k.key;
    os << "rotgen sweep " << q.scene << "\n"
       << "  model   " << scene.model.name << " (" << scene.model.file << "), "
       << to_string(scene.form) << " form, method " << scene.integrator.method << "\n"
       << "  members " << outcomes.size() << " (" << mode_name(plan.mode) << " over " << keys
       << "), " << outcomes.size() - failed << " ok, " << failed << " failed; " << workers << "\n";
    if (!lanes.empty())
        os << "  lanes   " << in_lanes << " of " << outcomes.size() << " members in batches of "
           << q.lanes << " (" << lanes << ")\n";
    os << "  steps   " << steps << " accepted; " << evals << " RHS evaluations\n"
       << "  time    " << short_number(seconds) << " s running the members ("
       << short_number(outcomes.empty() ? 0 : outcomes.size() / seconds) << " members/s)\n";
}

// DIR/trajectories.h5 from the members' samples.
void write_h5(const std::string& path, const scene_spec& scene, const sweep_plan& plan,
              const std::vector<std::vector<double>>& rows, const summary_layout& layout,
              const std::vector<member_outcome>& outcomes) {
    trajectory_file f;
    f.columns = {"t"};
    f.columns.insert(f.columns.end(), layout.columns.begin(), layout.columns.end());
    for (const auto& k : plan.keys)
        f.keys.push_back(k.key);
    std::ifstream in(scene.file, std::ios::binary);
    f.scene_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    f.scene_file = scene.file;
    f.members = outcomes.size();
    f.samples = layout.samples;
    f.values = &rows;
    for (const auto& o : outcomes)
        f.data.push_back(&o.trajectory);
    write_trajectories(path, f);
}

// One line per failed member (the first ten), on stderr.
void report_failures(const std::string& scene_file, const std::vector<member_outcome>& outcomes) {
    constexpr std::size_t shown = 10;
    std::size_t failed = 0;
    for (std::size_t m = 0; m < outcomes.size(); ++m)
        if (!outcomes[m].ok() && ++failed <= shown)
            std::cerr << "rotgen: error: " << scene_file << ": member " << m << ": "
                      << outcomes[m].status << "\n";
    if (failed > shown)
        std::cerr << "rotgen: error: " << failed - shown << " more members failed (status in "
                  << "summary.csv)\n";
}

// The scene's ensemble, prepared: the plan, the members' values, the derivation and kernels.
struct ensemble {
    scene_spec scene;
    sweep_plan plan;
    std::vector<std::vector<double>> rows;
    std::unique_ptr<prepared_scene> prepared;
    summary_layout layout;
    std::unique_ptr<lane_kernels> lanes; // with --lanes W > 1

    ensemble(const sweep_request& q, stage_timings& timings)
        : scene(load_scene(q.scene)), plan(read_sweep_plan(scene, q.vary)),
          rows(member_rows(plan)) {
        check_files(q, scene);
        if (q.lanes > 1) lane_check(scene);
        prepared = std::make_unique<prepared_scene>(scene, timings);
        prepared->compile_all(timings);
        layout = layout_of(*prepared);
        if (q.lanes > 1) lanes = std::make_unique<lane_kernels>(compile_lanes(*prepared, timings));
    }
};

// Members first .. first+count-1 in lanes (run/lanes.hpp); those a batch cannot carry alone.
std::vector<member_outcome> run_batch(const ensemble& e, const member_values& base,
                                      std::size_t first, std::size_t count, bool trajectories) {
    std::vector<member_values> values;
    for (std::size_t m = first; m < first + count; ++m)
        values.push_back(member_of(e.plan, base, e.rows[m]));
    const std::vector<std::optional<run_result>> results = run_lanes(*e.prepared, *e.lanes, values);
    std::vector<member_outcome> out;
    for (std::size_t k = 0; k < count; ++k) {
        out.push_back(results[k] ? outcome_of(*e.prepared, e.layout, *results[k], trajectories)
                                 : run_one(*e.prepared, e.layout, values[k], trajectories));
        out.back().in_lanes = results[k].has_value();
    }
    return out;
}

// Every member's outcome, in member order: one at a time, or in batches of lanes.
std::vector<member_outcome> run_members(const mpi_session& session, const sweep_request& q,
                                        const ensemble& e, unsigned jobs,
                                        const std::function<void(std::size_t)>& progress) {
    const member_values base = values_of(e.prepared->scene());
    if (e.lanes)
        return run_distributed(
            session, e.rows.size(), q.lanes, jobs,
            [&](std::size_t first, std::size_t count) {
                return run_batch(e, base, first, count, q.trajectories);
            },
            progress);
    return run_distributed(
        session, e.rows.size(), jobs,
        [&](std::size_t m) {
            return run_one(*e.prepared, e.layout, member_of(e.plan, base, e.rows[m]),
                           q.trajectories);
        },
        progress);
}

// The files and the report (rank 0 only). Returns the exit status.
int finish(const sweep_request& q, const ensemble& e, const std::string& workers,
           const std::vector<member_outcome>& outcomes, double seconds, atomic_file& summary_out,
           stage_timings& timings) {
    timings.time("write", summary_out.path(), [&] {
        write_summary(summary_out.stream(), e.plan, e.rows, e.layout, outcomes);
        summary_out.commit();
    });
    const std::string h5 = q.directory + "/trajectories.h5";
    if (q.trajectories)
        timings.time("write", h5,
                     [&] { write_h5(h5, e.scene, e.plan, e.rows, e.layout, outcomes); });
    std::ostringstream discarded;
    std::ostream& summary = q.quiet ? discarded : std::cerr;
    print_summary(summary, q, e.scene, e.plan, outcomes, workers, e.lanes ? e.lanes->arch : "",
                  seconds);
    summary << "  wrote   " << summary_out.path() << " (" << outcomes.size() << " members)\n";
    if (q.trajectories)
        summary << "  wrote   " << h5 << " (" << outcomes.size() << " x " << e.layout.samples
                << " x " << e.layout.columns.size() + 1 << ")\n";
    if (q.timings) timings.print(std::cerr);
    bool failed = false;
    for (const auto& o : outcomes)
        failed = failed || !o.ok();
    if (!failed) return 0;
    report_failures(q.scene, outcomes);
    return 3;
}

// Rank 0 prepares (and compiles into the cache) and opens its outputs first; then the other ranks
// prepare. A failure on any rank stops every rank; rank 0 reports it.
std::unique_ptr<ensemble> prepare_everywhere(const mpi_session& session, const sweep_request& q,
                                             stage_timings& timings,
                                             std::unique_ptr<atomic_file>& summary_out) {
    std::unique_ptr<ensemble> e;
    std::exception_ptr failure;
    const auto attempt = [&] {
        try {
            e = std::make_unique<ensemble>(q, timings);
            if (session.rank() != 0) return;
            make_directory(q.directory);
            summary_out = std::make_unique<atomic_file>(
                q.directory + "/summary.csv",
                std::vector<std::string>{q.scene, e->scene.model.file});
        } catch (...) {
            failure = std::current_exception();
        }
    };
    if (session.rank() == 0) attempt();
    if (!session.all(session.rank() != 0 || !failure)) {
        if (failure) std::rethrow_exception(failure);
        return nullptr; // rank 0 reports it
    }
    if (session.rank() != 0) attempt();
    if (!session.all(!failure)) {
        if (session.rank() == 0)
            throw std::runtime_error("another MPI rank could not prepare the scene");
        return nullptr;
    }
    return e;
}

} // namespace

int sweep(const sweep_request& q) {
    const mpi_session session;
    stage_timings timings;
    std::unique_ptr<atomic_file> summary_out;
    const std::unique_ptr<ensemble> e = prepare_everywhere(session, q, timings, summary_out);
    if (!e) return 2; // a rank other than 0: rank 0 reported the error
    const bool root = session.rank() == 0;
    progress_line progress(0, double(e->rows.size()), root && !q.quiet, "members");
    // under mpirun a rank per core, each with one thread, unless -j says otherwise
    const unsigned jobs = q.jobs != 0 ? q.jobs : session.size() > 1 ? 1 : all_cores();
    const auto start = std::chrono::steady_clock::now();
    const std::vector<member_outcome> outcomes =
        timings.time("members", std::to_string(e->rows.size()), [&] {
            return run_members(session, q, *e, jobs,
                               [&](std::size_t done) { progress.update(double(done)); });
        });
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    progress.finish();
    if (!root) return 0;
    const std::string workers =
        std::to_string(jobs) + (jobs == 1 ? " thread" : " threads") +
        (session.size() > 1 ? " on each of " + std::to_string(session.size()) + " MPI ranks" : "");
    return finish(q, *e, workers, outcomes, seconds, *summary_out, timings);
}

} // namespace rotgen
