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
#include "sweep/batch.hpp"
#include "sweep/binding.hpp"
#include "sweep/distribute.hpp"
#include "sweep/journal.hpp"
#include "sweep/members.hpp"
#include "sweep/outcome.hpp"
#include "sweep/parallel.hpp"
#include "sweep/trajectories.hpp"
#include "sweep/writer.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
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
// Returns whether it was created.
bool make_directory(const std::string& dir) {
    if (dir.empty() || dir == "-")
        throw user_error({"rotgen sweep"}, "-o needs a directory (the sweep writes several files)");
    struct stat st {};
    if (::stat(dir.c_str(), &st) == 0) {
        if (!S_ISDIR(st.st_mode)) throw user_error({dir}, "not a directory");
        return false;
    }
    if (::mkdir(dir.c_str(), 0755) != 0)
        throw user_error({dir},
                         std::string("cannot create the directory: ") + std::strerror(errno));
    return true;
}

// Members a journal chunk: about a 64th of the sweep, 1 to 4,096, a whole number of lane batches
// (a resumed run's batches are an uninterrupted one's).
std::size_t chunk_of(std::size_t members, unsigned lanes) {
    const std::size_t c = std::clamp<std::size_t>(members / 64, 1, 4096);
    return (c + lanes - 1) / lanes * lanes;
}

// Where the files go, checked before any derivation: a journal in DIR is refused unless --resume
// (then it must be this sweep's), and --resume goes on after its last whole chunk.
writer_setup files_of(const sweep_request& q, const scene_spec& scene, std::size_t members) {
    writer_setup w;
    w.dir = q.directory;
    w.trajectories = q.trajectories;
    w.chunk = chunk_of(members, q.lanes);
    std::vector<std::string> keys = q.vary; // with method auto, its choice is part of the hash
    if (!scene.integrator.auto_choice.empty())
        keys.push_back("auto " + scene.integrator.method + " " +
                       short_number(scene.integrator.rtol, 17) + " " + to_string(scene.form));
    w.hash = journal_hash(scene.file, scene.model.file, keys, q.trajectories, q.lanes);
    const journal_names names = journal_in(q.directory);
    const journal_found found = read_journal(names, w.chunk, members);
    if (!found.exists) return w;
    if (!q.resume)
        throw user_error({names.summary},
                         "the journal of an interrupted sweep (" + std::to_string(found.members) +
                             " members finished): add --resume to finish it, or remove the "
                             "folder's *.partial* files to start again");
    if (found.hash != w.hash)
        throw user_error({names.stamp}, "this journal is of another scene or other options "
                                        "(--vary, --trajectories, --lanes); resume it with the "
                                        "command that made it, or remove the folder's "
                                        "*.partial* files");
    if (found.members > 0) w.resume = found; // else it starts again, as if there were none
    return w;
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

// `lanes`: the batch kernel's target with --lanes W > 1, else empty.
void print_summary(std::ostream& os, const sweep_request& q, const scene_spec& scene,
                   const sweep_plan& plan, const sweep_writer& w, const std::string& workers,
                   const std::string& lanes, double seconds) {
    std::string keys;
    for (const auto& k : plan.keys)
        keys += (keys.empty() ? "" : ", ") + k.key;
    const std::size_t all = w.first() + w.members();
    os << "rotgen sweep " << q.scene << "\n"
       << "  model   " << scene.model.name << " (" << scene.model.file << "), "
       << to_string(scene.form) << " form, method "
       << (scene.integrator.auto_choice.empty() ? scene.integrator.method
                                                : "auto: " + scene.integrator.auto_choice)
       << "\n"
       << "  members " << all << " (" << mode_name(plan.mode) << " over " << keys << "), "
       << all - w.failed() << " ok, " << w.failed() << " failed; " << workers << "\n";
    if (!lanes.empty())
        os << "  lanes   " << w.in_lanes() << " of " << w.members() << " members in batches of "
           << q.lanes << " (" << lanes << ")\n";
    if (w.first() > 0)
        os << "  resumed after the journal's " << w.first() << " members (the lines below: the "
           << w.members() << " run now)\n";
    os << "  steps   " << w.steps() << " accepted; " << w.rhs_evals() << " RHS evaluations\n"
       << "  time    " << format_duration(seconds) << " running the members ("
       << short_number(w.members() == 0 ? 0 : double(w.members()) / seconds) << " members/s)\n";
}

// One line per failed member (the first ten), on stderr.
void report_failures(const std::string& scene_file, const sweep_writer& w) {
    for (const auto& [m, status] : w.failures())
        std::cerr << "rotgen: error: " << scene_file << ": member " << m << ": " << status << "\n";
    if (w.failed() > w.failures().size())
        std::cerr << "rotgen: error: " << w.failed() - w.failures().size()
                  << " more members failed (status in summary.csv)\n";
}

// The scene's ensemble, prepared: the plan, the members' values, the derivation and kernels.
struct ensemble {
    scene_spec scene;
    sweep_plan plan;
    member_table table;
    std::unique_ptr<prepared_scene> prepared;
    summary_layout layout;
    std::unique_ptr<lane_kernels> lanes; // with --lanes W > 1
    writer_setup files;                  // rank 0

    ensemble(const sweep_request& q, bool root, stage_timings& timings)
        : scene(load_scene(q.scene, "sweep")), plan(read_sweep_plan(scene, q.vary)), table(plan) {
        // method auto: rank 0 (first to prepare) tunes and caches; the other ranks read its choice
        if (q.resolve) q.resolve(scene);
        // what cannot be done is refused before any derivation or compilation
        check_files(q, scene);
        if (root) {
            check_room(q.directory, estimated_output(scene, plan, table.size(), q.trajectories),
                       table.size());
            files = files_of(q, scene, table.size());
        }
        if (q.lanes > 1) lane_check(scene);
        prepared = std::make_unique<prepared_scene>(scene, timings);
        if (!q.trajectories) prepared->keep_last_row_only();
        prepared->compile_all(timings);
        layout = layout_of(*prepared);
        if (q.lanes > 1)
            lanes = std::make_unique<lane_kernels>(compile_lanes(*prepared, timings, q.lanes));
    }
};

// Outcomes that may wait in memory: about 32 MB of them, and enough for every thread. The tests'
// hook ROTGEN_TEST_SWEEP_WINDOW=N makes it N members (at least a batch of lanes), so that a small
// sweep runs against the window's bound.
std::size_t window_of(const sweep_request& q, const ensemble& e, unsigned jobs, int ranks) {
    if (const char* v = std::getenv("ROTGEN_TEST_SWEEP_WINDOW"))
        return std::max<std::size_t>(std::strtoul(v, nullptr, 10), q.lanes);
    const std::size_t numbers =
        1 + e.layout.columns.size() + e.layout.events.size() + e.layout.invariants.size() +
        (q.trajectories ? e.layout.samples * trajectory_columns(e.layout).size() : 0);
    const std::size_t budget = std::size_t(32) << 20, member = 256 + 8 * numbers;
    const std::size_t least = 4 * std::size_t(q.lanes) * (std::size_t(jobs) + std::size_t(ranks));
    return std::min(std::max(budget / member, least), std::max<std::size_t>(e.table.size(), 1));
}

// Runs members `from` .. the last (`out`, on rank 0, numbers them from 0), each outcome through
// `out` in member order: one at a time, or in batches of lanes. Returns what each rank did (rank
// 0).
std::vector<rank_work> run_members(const mpi_session& session, const sweep_request& q,
                                   const ensemble& e, std::size_t from, unsigned jobs,
                                   in_order* out, const std::function<void(std::size_t)>& progress,
                                   work_clock::time_point start) {
    const member_values base = values_of(e.prepared->scene());
    const sweep_members members{*e.prepared, e.layout,      e.plan,
                                e.table,     e.lanes.get(), q.trajectories};
    return run_distributed(
        session, e.table.size() - from, e.lanes ? q.lanes : 1, jobs,
        [&](std::size_t first, std::size_t n) {
            std::vector<member_outcome> o = run_neighbours(members, base, from + first, n);
            for (std::size_t k = 0; k < o.size(); ++k) {
                const std::size_t m = from + first + k;
                o[k].summary_row = summary_row_of(m, e.table.row(m), e.layout, o[k]);
            }
            return o;
        },
        out, progress, start);
}

// `--timings`: a line per rank (or for this process) on how its threads were used in `seconds`:
//   rotgen: rank 1   1024 members from 0.002 to 0.282 s, 1 thread busy 0.276 s (97% of the run)
void print_balance(std::ostream& os, const std::vector<rank_work>& ranks, unsigned jobs,
                   double seconds) {
    const std::string threads = std::to_string(jobs) + (jobs == 1 ? " thread" : " threads");
    for (std::size_t r = 0; r < ranks.size(); ++r) {
        const rank_work& w = ranks[r];
        const double share = seconds > 0 ? 100 * w.busy / (jobs * seconds) : 0;
        char line[160];
        std::snprintf(line, sizeof line,
                      "   %zu members from %.3f to %.3f s, %s busy %.3f s (%.0f%% of the run)",
                      w.members, w.first, w.last, threads.c_str(), w.busy, share);
        os << "rotgen: " << (ranks.size() > 1 ? "rank " + std::to_string(r) : "threads") << line
           << '\n';
    }
}

// The files' completion and the report (rank 0 only). Returns the exit status.
int finish(const sweep_request& q, const ensemble& e, const std::string& workers, sweep_writer& w,
           double seconds, stage_timings& timings) {
    timings.time("write", w.summary_path(), [&] { w.commit(); });
    std::ostringstream discarded;
    std::ostream& summary = q.quiet ? discarded : std::cout; // standard output: no data there
    print_summary(summary, q, e.prepared->scene(), e.plan, w, workers, e.lanes ? e.lanes->arch : "",
                  seconds);
    const std::size_t all = w.first() + w.members();
    summary << "  wrote   " << w.summary_path() << " (" << all << " members)\n";
    if (q.trajectories)
        summary << "  wrote   " << w.trajectories_path() << " (" << all << " x " << e.layout.samples
                << " x " << trajectory_columns(e.layout).size() << ")\n";
    if (q.timings) timings.print(std::cerr);
    if (w.failed() == 0) return 0;
    report_failures(q.scene, w);
    return 3;
}

// 'u' (a user_error) or 'i' (any other failure), then its one-line message.
std::string describe(const std::exception_ptr& failure) {
    try {
        std::rethrow_exception(failure);
    } catch (const user_error& e) {
        return "u" + e.message();
    } catch (const std::exception& e) {
        return "i" + std::string(e.what());
    } catch (...) {
        return "ian unknown failure";
    }
}

// After a failure on some rank (session.all said so), rank 0 throws the first: its own, or the
// lowest other rank's, named (a user_error stays one: exit 2). The other ranks return and exit 0:
// mpirun's status is then rank 0's, and it has no failed rank to end rank 0 for before rank 0 has
// printed the error (a rank that exited 1 first had mpirun end rank 0 with SIGTERM, the error
// unsaid).
void rethrow_first(const mpi_session& session, const std::exception_ptr& failure) {
    const bool root = session.rank() == 0;
    const std::string mine = failure ? describe(failure) : "";
    const std::string other =
        session.first_message(root || !failure ? "" : mine + " (" + session.name() + ")");
    if (!root) return;
    if (failure) std::rethrow_exception(failure);
    if (other.empty()) throw std::runtime_error("another MPI rank failed");
    if (other[0] == 'u') throw user_error({}, other.substr(1));
    throw std::runtime_error(other.substr(1));
}

// ROTGEN_BINDING's policy, checked on every rank before anything is written; rank 0 throws the
// error, the others return nothing.
std::optional<binding_policy> checked_binding(const mpi_session& session) {
    std::optional<binding_policy> policy;
    std::exception_ptr failure;
    try {
        policy = binding_of_environment();
    } catch (const user_error&) {
        failure = std::current_exception();
    }
    if (session.all(!failure)) return policy;
    rethrow_first(session, failure);
    return std::nullopt;
}

// Rank 0 prepares (and compiles into the cache) and opens its outputs first; then one rank of
// every other node (a node-local cache is filled once a node, not once a rank: a compilation can
// take seconds and hundreds of MB); then the rest, who find the kernels in the cache. A failure on
// any rank stops every rank: rank 0 reports it (rethrow_first), and the others return null.
std::unique_ptr<ensemble> prepare_everywhere(const mpi_session& session, const sweep_request& q,
                                             stage_timings& timings,
                                             std::unique_ptr<sweep_writer>& writer) {
    std::unique_ptr<ensemble> e;
    std::exception_ptr failure;
    const auto attempt = [&] {
        try {
            e = std::make_unique<ensemble>(q, session.rank() == 0, timings);
            if (session.rank() != 0) return;
            e->files.made_dir = make_directory(q.directory);
            writer =
                std::make_unique<sweep_writer>(e->files, e->scene, e->plan, e->table, e->layout);
        } catch (...) {
            failure = std::current_exception();
        }
    };
    const int mine = session.rank() == 0 ? 0 : session.node_rank() == 0 ? 1 : 2;
    for (int stage = 0; stage < 3; ++stage) {
        if (mine == stage) attempt();
        if (session.all(!failure)) continue;
        rethrow_first(session, failure);
        return nullptr;
    }
    return e;
}

// The threads of a node's ranks together, and the cores their masks hold together.
struct node_load {
    std::size_t threads, cores;
    bool elsewhere; // some node (this one or another) runs more threads than it has cores
    bool crowded() const { return threads > cores; }
};

// Where the threads run, when rotgen bound them again (sweep/binding.hpp), and a warning when a
// rank's threads outnumber its cores (`cores`, the least over the ranks) or, failing that, when a
// node's ranks run more threads than the cores they may run on (`node`, this rank's node's): the
// threads then share cores and run no faster than those.
std::string placement(const mpi_session& session, unsigned jobs, const thread_cores& placed,
                      std::size_t cores, const node_load& node) {
    const auto count = [](std::size_t n, const char* what) {
        return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
    };
    std::string line;
    if (placed.rebound && !placed.shared)
        line = "\n  cores   the launcher bound each rank to " + count(placed.bound, "core") +
               ", too few for its threads: rotgen gave it " + count(placed.cores, "core") +
               " of its own (ROTGEN_BINDING=keep keeps the launcher's binding)";
    const std::string who = session.size() > 1 ? "an MPI rank" : "this process";
    if (jobs > cores)
        return line + "\n  warning " + count(jobs, "thread") + " share the " +
               count(cores, "core") + " " + who + " may run on" +
               (session.launched()
                    ? " (the launcher's binding or a batch system's cpuset: give mpirun "
                      "--bind-to none, or --map-by slot:PE=" +
                          std::to_string(jobs) + ")"
                    : " (its CPU affinity: taskset, a batch system's cpuset)");
    if (node.crowded())
        return line + "\n  warning the " + count(std::size_t(session.node_size()), "rank") +
               " on this node run " + count(node.threads, "thread") + " on its " +
               count(node.cores, "core");
    if (node.elsewhere)
        return line + "\n  warning the ranks on a node run more threads than its cores";
    return line;
}

// "1 thread on each of 2 MPI ranks, lanes of 4 (avx2)"; with MPI, the members each rank ran.
std::string workers_of(const mpi_session& session, unsigned jobs, const std::string& placed,
                       const std::vector<rank_work>& ran) {
    std::string w =
        std::to_string(jobs) + (jobs == 1 ? " thread" : " threads") +
        (session.size() > 1 ? " on each of " + std::to_string(session.size()) + " MPI ranks" : "");
    if (session.size() > 1) {
        w += "\n  ranks   members run by rank 0, 1, ...:";
        for (std::size_t r = 0; r < ran.size(); ++r)
            w += (r == 0 ? " " : ", ") + std::to_string(ran[r].members);
    }
    return w + placed;
}

} // namespace

int sweep(const sweep_request& q) {
    const mpi_session session;
    if (session.rank() == 0)
        journal_not_yet();
    else
        journal_elsewhere();
    const std::optional<binding_policy> binding = checked_binding(session);
    if (!binding) return 0; // rank 0 reports the error
    stage_timings timings;
    std::unique_ptr<sweep_writer> writer;
    const std::unique_ptr<ensemble> e = prepare_everywhere(session, q, timings, writer);
    if (!e) return 0; // rank 0 reports the error
    const bool root = session.rank() == 0;
    // the members a journal holds are not run again (--resume)
    const std::size_t from = session.broadcast(root ? writer->first() : 0);
    progress_line progress(double(from), double(e->table.size()), root && !q.quiet, "members");
    // under mpirun a rank per core, each with one thread, unless -j says otherwise
    const unsigned jobs = q.jobs != 0 ? q.jobs : session.size() > 1 ? 1 : all_cores();
    const thread_cores placed =
        place_threads(jobs, session.launched(), session.node_rank(), session.node_size(), *binding);
    const std::size_t cores = session.least(placed.cores);
    node_load node{std::size_t(session.node_size()) * jobs, cpus_in(session.node_union(cpu_mask())),
                   false};
    node.elsewhere = !session.all(!node.crowded());
    std::unique_ptr<in_order> out;
    if (root)
        out = std::make_unique<in_order>(
            e->table.size() - from, window_of(q, *e, jobs, session.size()),
            [&](std::size_t m, member_outcome&& o) { writer->add(from + m, std::move(o)); });
    const auto start = std::chrono::steady_clock::now();
    const std::vector<rank_work> ran =
        timings.time("members", std::to_string(e->table.size() - from), [&] {
            return run_members(
                session, q, *e, from, jobs, out.get(),
                [&](std::size_t done) { progress.update(double(from + done)); }, start);
        });
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    progress.finish();
    if (!root) return 0;
    const int status =
        finish(q, *e, workers_of(session, jobs, placement(session, jobs, placed, cores, node), ran),
               *writer, seconds, timings);
    if (q.timings) print_balance(std::cerr, ran, jobs, seconds);
    return status;
}

} // namespace rotgen
