#include "sweep/sweep.hpp"

#include "run/prepared.hpp"
#include "scene/scene.hpp"
#include "support/atomic_file.hpp"
#include "support/error.hpp"
#include "support/format.hpp"
#include "support/progress.hpp"
#include "support/timings.hpp"
#include "sweep/members.hpp"
#include "sweep/outcome.hpp"
#include "sweep/parallel.hpp"
#include "sweep/trajectories.hpp"

#include <sys/stat.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
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

std::string mode_name(sweep_mode m) {
    return m == sweep_mode::grid ? "grid" : m == sweep_mode::zip ? "zip" : "random";
}

// Every member, on `jobs` threads taking the next member as they finish one; each outcome in its
// member's slot.
std::vector<member_outcome> run_members(const prepared_scene& prepared,
                                        const summary_layout& layout, const sweep_plan& plan,
                                        const std::vector<std::vector<double>>& rows, unsigned jobs,
                                        bool trajectories, progress_line& progress) {
    const member_values base = values_of(prepared.scene());
    std::vector<member_outcome> outcomes(rows.size());
    std::atomic<std::size_t> next{0}, done{0};
    run_pool(
        jobs,
        [&] {
            const std::size_t m = next++;
            return m < rows.size() ? m : none;
        },
        [&](std::size_t m) {
            outcomes[m] = run_one(prepared, layout, member_of(plan, base, rows[m]), trajectories);
            ++done;
        },
        [&] { progress.update(double(done)); });
    return outcomes;
}

void print_summary(std::ostream& os, const sweep_request& q, const scene_spec& scene,
                   const sweep_plan& plan, const std::vector<member_outcome>& outcomes,
                   unsigned jobs, double seconds) {
    std::uint64_t steps = 0, evals = 0;
    std::size_t failed = 0;
    for (const auto& o : outcomes) {
        steps += o.steps, evals += o.rhs_evals;
        failed += o.ok() ? 0 : 1;
    }
    std::string keys;
    for (const auto& k : plan.keys)
        keys += (keys.empty() ? "" : ", ") + k.key;
    os << "rotgen sweep " << q.scene << "\n"
       << "  model   " << scene.model.name << " (" << scene.model.file << "), "
       << to_string(scene.form) << " form, method " << scene.integrator.method << "\n"
       << "  members " << outcomes.size() << " (" << mode_name(plan.mode) << " over " << keys
       << "), " << outcomes.size() - failed << " ok, " << failed << " failed; " << jobs
       << (jobs == 1 ? " thread\n" : " threads\n") << "  steps   " << steps << " accepted; "
       << evals << " RHS evaluations\n"
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
    std::size_t shown = 0, failed = 0;
    for (std::size_t m = 0; m < outcomes.size(); ++m) {
        if (outcomes[m].ok()) continue;
        if (++failed <= 10)
            std::cerr << "rotgen: error: " << scene_file << ": member " << m << ": "
                      << outcomes[m].status << "\n",
                ++shown;
    }
    if (failed > shown)
        std::cerr << "rotgen: error: " << failed - shown << " more members failed (status in "
                  << "summary.csv)\n";
}

} // namespace

int sweep(const sweep_request& q) {
    const scene_spec scene = load_scene(q.scene);
    const sweep_plan plan = read_sweep_plan(scene, q.vary);
    const std::vector<std::vector<double>> rows = member_rows(plan);
    stage_timings timings;
    const prepared_scene prepared(scene, timings);
    prepared.compile_all(timings);
    const summary_layout layout = layout_of(prepared);

    make_directory(q.directory);
    const std::vector<std::string> inputs{q.scene, scene.model.file};
    atomic_file summary_out(q.directory + "/summary.csv", inputs);
    progress_line progress(0, double(rows.size()), !q.quiet, "members");
    const unsigned jobs = q.jobs == 0 ? all_cores() : q.jobs;
    const auto start = std::chrono::steady_clock::now();
    const std::vector<member_outcome> outcomes =
        timings.time("members", std::to_string(rows.size()), [&] {
            return run_members(prepared, layout, plan, rows, jobs, q.trajectories, progress);
        });
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    progress.finish();
    timings.time("write", summary_out.path(), [&] {
        write_summary(summary_out.stream(), plan, rows, layout, outcomes);
        summary_out.commit();
    });
    if (q.trajectories)
        timings.time("write", q.directory + "/trajectories.h5", [&] {
            write_h5(q.directory + "/trajectories.h5", scene, plan, rows, layout, outcomes);
        });
    std::ostringstream discarded;
    std::ostream& summary = q.quiet ? discarded : std::cerr;
    print_summary(summary, q, scene, plan, outcomes, jobs, seconds);
    summary << "  wrote   " << summary_out.path() << " (" << outcomes.size() << " members)\n";
    if (q.trajectories)
        summary << "  wrote   " << q.directory << "/trajectories.h5 (" << outcomes.size() << " x "
                << layout.samples << " x " << layout.columns.size() + 1 << ")\n";
    if (q.timings) timings.print(std::cerr);
    bool failed = false;
    for (const auto& o : outcomes)
        failed = failed || !o.ok();
    if (!failed) return 0;
    report_failures(q.scene, outcomes);
    return 3;
}

} // namespace rotgen
