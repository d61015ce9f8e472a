#include "sweep/writer.hpp"

#include "support/atomic_file.hpp"
#include "support/error.hpp"
#include "support/format.hpp"
#include "support/signals.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

namespace rotgen {

namespace {

constexpr std::size_t failures_kept = 10;

std::string gigabytes(double bytes) {
    return short_number(bytes / 1e9) + " GB";
}

trajectory_file header_of(const scene_spec& scene, const sweep_plan& plan,
                          const summary_layout& layout, std::size_t members) {
    trajectory_file f;
    f.columns = trajectory_columns(layout);
    for (const auto& k : plan.keys)
        f.keys.push_back(k.key);
    std::ifstream in(scene.file, std::ios::binary);
    f.scene_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    f.scene_file = scene.file;
    f.members = members;
    f.samples = layout.samples;
    return f;
}

[[noreturn]] void cannot_write(const std::string& path) {
    throw user_error({path}, std::string("cannot write: ") + std::strerror(errno));
}

void write_all(int fd, const std::string& bytes, const std::string& path) {
    for (std::size_t done = 0; done < bytes.size();) {
        const ssize_t k = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) cannot_write(path);
        done += std::size_t(k);
    }
}

// A file of DIR that is one of the command's inputs is refused: rotgen never writes over them.
void check_not_input(const std::string& path, const scene_spec& scene) {
    struct stat out {
    }, in{};
    if (::stat(path.c_str(), &out) != 0) return;
    for (const std::string& input : {scene.file, scene.model.file})
        if (::stat(input.c_str(), &in) == 0 && in.st_dev == out.st_dev && in.st_ino == out.st_ino)
            throw user_error({path},
                             "refusing to write over '" + input + "', a file this command reads");
}

// ROTGEN_TEST_SWEEP_INTERRUPT=N[:INT], the tests' hook: SIGTERM (or SIGINT) once N chunks are
// in the journal (0: once it is started, before any member). -1 without it.
long interrupt_after() {
    const char* v = std::getenv("ROTGEN_TEST_SWEEP_INTERRUPT");
    return v ? std::strtol(v, nullptr, 10) : -1;
}

void interrupt_now() {
    const char* v = std::getenv("ROTGEN_TEST_SWEEP_INTERRUPT");
    ::raise(v && std::strstr(v, ":INT") ? SIGINT : SIGTERM);
}

} // namespace

const std::vector<std::string>& sweep_set_files() {
    static const std::vector<std::string> names{"summary.csv", "trajectories.h5",
                                                "summary.partial.csv", "trajectories.partial.h5",
                                                "sweep.partial"};
    return names;
}

std::uint64_t estimated_output(const scene_spec& scene, const sweep_plan& plan, std::size_t members,
                               bool trajectories) {
    std::uint64_t columns = 0;
    for (const auto& name : scene.record)
        columns += record_columns(name).size();
    // with sensitivities each column has a d(...) column per key (all_initial: about 7, the body
    // form's state)
    columns *= 1 + (scene.sensitivities.all_initial ? 7 : scene.sensitivities.keys.size());
    // a row: the varied values, final.t and the columns, the events, the energy's drift, 24
    // bytes each, and the member, steps, rhs_evals and status in about 40
    const std::uint64_t row = 24 * (plan.keys.size() + 1 + columns + scene.events.size() + 1) + 40;
    std::uint64_t bytes = row * members;
    if (trajectories)
        bytes += 8 * std::uint64_t(members) *
                     (std::uint64_t(scene.samples) * (1 + columns) + plan.keys.size()) +
                 65536;
    return bytes;
}

void check_room(const std::string& dir, std::uint64_t bytes, std::size_t members) {
    struct statvfs fs {};
    std::string where = dir;
    if (::statvfs(where.c_str(), &fs) != 0) {
        const auto slash = dir.find_last_of('/');
        where = slash == std::string::npos ? "." : slash == 0 ? "/" : dir.substr(0, slash);
        if (::statvfs(where.c_str(), &fs) != 0) return; // the directory's creation reports it
    }
    const double free = double(fs.f_bavail) * double(fs.f_frsize);
    if (double(bytes) > free)
        throw user_error({dir}, "the sweep would write about " + gigabytes(double(bytes)) + " (" +
                                    std::to_string(members) + " members), more than the " +
                                    gigabytes(free) + " free there");
}

sweep_writer::sweep_writer(const writer_setup& setup, const scene_spec& scene,
                           const sweep_plan& plan, const member_table& table,
                           const summary_layout& layout)
    : m_setup(setup), m_names(journal_in(setup.dir)), m_table(table), m_layout(layout) {
    for (const auto& name : sweep_set_files())
        check_not_input(setup.dir + "/" + name, scene);
    m_interrupt_after = interrupt_after();
    const trajectory_file header = header_of(scene, plan, layout, table.size());
    try {
        if (setup.resume.exists)
            go_on(header);
        else
            start(header, plan);
    } catch (...) {
        m_h5.reset();
        journal_abandon(0); // what the journal had before this run, or nothing
        forget_removed_stamp();
        journal_unwatch();
        if (m_fd >= 0) ::close(m_fd);
        throw;
    }
    if (m_interrupt_after == 0) interrupt_now();
}

void sweep_writer::go_on(const trajectory_file& header) {
    m_first = m_setup.resume.members;
    m_failed = m_setup.resume.failed;
    m_bytes = m_setup.resume.bytes;
    m_fd = ::open(m_names.summary.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (m_fd < 0 || ::ftruncate(m_fd, off_t(m_bytes)) != 0) cannot_write(m_names.summary);
    journal_watch(m_names, m_fd, m_bytes, m_first, false);
    if (m_setup.trajectories)
        m_h5 = std::make_unique<trajectory_stream>(m_names.trajectories, header, m_first);
}

void sweep_writer::start(const trajectory_file& header, const sweep_plan& plan) {
    write_file_atomically(m_names.stamp, "rotgen sweep journal: add --resume to the command that "
                                         "made it to finish it\nhash " +
                                             m_setup.hash + "\n");
    m_fd =
        ::open(m_names.summary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0644);
    if (m_fd < 0) {
        std::remove(m_names.stamp.c_str());
        cannot_write(m_names.summary);
    }
    journal_watch(m_names, m_fd, 0, 0, m_setup.made_dir);
    std::ostringstream head;
    write_summary_header(head, plan, m_layout);
    write_all(m_fd, head.str(), m_names.summary);
    m_bytes = head.str().size();
    journal_committed(m_bytes, 0);
    if (m_setup.trajectories)
        m_h5 = std::make_unique<trajectory_stream>(
            m_names.trajectories, header, [&](std::size_t first, std::size_t n) {
                std::vector<double> flat;
                for (std::size_t m = first; m < first + n; ++m) {
                    const std::vector<double> row = m_table.row(m);
                    flat.insert(flat.end(), row.begin(), row.end());
                }
                return flat;
            });
}

sweep_writer::~sweep_writer() {
    if (m_fd < 0) return;
    m_h5.reset();
    journal_abandon(0);
    forget_removed_stamp();
    journal_unwatch();
    ::close(m_fd);
}

// journal_abandon removes the stamp when no member had finished: an interruption from then on
// (mpirun ending rank 0 while it reports another rank's error) must not say it was written.
void sweep_writer::forget_removed_stamp() const {
    if (::access(m_names.stamp.c_str(), F_OK) != 0) note_removed(m_names.stamp);
}

void sweep_writer::add(std::size_t member, member_outcome&& o) {
    m_rows += o.summary_row;
    if (m_h5) m_h5->add(o.trajectory);
    ++m_members;
    m_in_lanes += o.in_lanes ? 1 : 0;
    m_steps += o.steps;
    m_evals += o.rhs_evals;
    if (!o.ok() && ++m_failed <= failures_kept) m_failures.emplace_back(member, o.status);
    if (m_members % m_setup.chunk == 0) end_chunk();
}

void sweep_writer::end_chunk() {
    if (m_h5) m_h5->flush();
    write_all(m_fd, m_rows, m_names.summary);
    m_bytes += m_rows.size();
    m_rows.clear();
    journal_committed(m_bytes, m_first + m_members);
    if (long(++m_chunks) == m_interrupt_after) interrupt_now();
}

void sweep_writer::commit() {
    if (!m_rows.empty()) end_chunk();
    if (m_h5) m_h5->close();
    journal_unwatch();
    if (::close(m_fd) != 0) cannot_write(m_names.summary);
    m_fd = -1;
    for (const auto& name : sweep_set_files()) { // an earlier sweep's files this run replaces
        const std::string path = m_setup.dir + "/" + name;
        if (path != m_names.summary && path != m_names.trajectories && path != summary_path() &&
            (path != trajectories_path() || !m_h5))
            std::remove(path.c_str());
    }
    if (m_h5 && std::rename(m_names.trajectories.c_str(), trajectories_path().c_str()) != 0)
        cannot_write(trajectories_path());
    if (std::rename(m_names.summary.c_str(), summary_path().c_str()) != 0)
        cannot_write(summary_path());
    std::remove(m_names.stamp.c_str());
    note_removed(m_names.stamp);
    note_written(summary_path());
    if (m_h5) note_written(trajectories_path());
}

} // namespace rotgen
