#include "sweep/journal.hpp"

#include "support/atomic_file.hpp"
#include "support/error.hpp"
#include "support/hash.hpp"
#include "support/signals.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstring>
#include <fstream>
#include <iterator>

namespace rotgen {

namespace {

std::string text_of(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool exists(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0;
}

// The handler's copy of the journal: fixed storage, no allocation in the handler.
constexpr std::size_t longest = 4096;
struct watched {
    std::array<char, longest> dir{}, stamp{}, summary{}, trajectories{};
    std::atomic<int> fd{-1};
    std::atomic<std::uint64_t> bytes{0};
    std::atomic<std::size_t> members{0};
    bool made_dir = false;
};
watched g_journal;

void copy(std::array<char, longest>& to, const std::string& from) {
    const std::size_t n = std::min(from.size(), longest - 1);
    std::memcpy(to.data(), from.data(), n);
    to[n] = '\0';
}

void say(const char* text) {
    for (std::size_t n = std::strlen(text), done = 0; done < n;) {
        const ssize_t k = ::write(2, text + done, n - done);
        if (k <= 0) return;
        done += std::size_t(k);
    }
}

extern "C" void on_interrupt(int sig) {
    journal_abandon(sig);
}

extern "C" void on_interrupt_before(int) {
    say("rotgen: interrupted; nothing written\n");
}

extern "C" void on_interrupt_quietly(int) {}

} // namespace

journal_names journal_in(const std::string& dir) {
    return {dir, dir + "/sweep.partial", dir + "/summary.partial.csv",
            dir + "/trajectories.partial.h5"};
}

std::string journal_hash(const std::string& scene_file, const std::string& model_file,
                         const std::vector<std::string>& vary, bool trajectories, unsigned lanes) {
    std::string all = text_of(scene_file) + '\0' + text_of(model_file) + '\0';
    for (const auto& v : vary)
        all += v + '\0';
    all += (trajectories ? "trajectories" : "summary") + std::string(1, '\0');
    all += "lanes " + std::to_string(lanes);
    return hex(fnv1a(all));
}

journal_found read_journal(const journal_names& names, std::size_t chunk, std::size_t count) {
    journal_found found;
    if (!exists(names.stamp)) return found;
    found.exists = true;
    const std::string stamp = text_of(names.stamp);
    const auto mark = stamp.find("hash ");
    if (mark == std::string::npos) throw user_error({names.stamp}, "not a sweep journal's stamp");
    found.hash = stamp.substr(mark + 5, 16);
    if (!exists(names.summary))
        throw user_error({names.summary},
                         "the journal has no summary (remove " + names.stamp + " to start again)");
    const std::string rows = text_of(names.summary);
    std::size_t line = rows.find('\n'); // the header
    if (line == std::string::npos) return found;
    found.bytes = line + 1;
    std::size_t at = found.bytes, rows_read = 0, failed = 0;
    for (std::size_t next;
         (next = rows.find('\n', at)) != std::string::npos && rows_read < count;) {
        const std::string member = std::to_string(rows_read) + ",";
        if (rows.compare(at, member.size(), member) != 0)
            throw user_error({names.summary, int(rows_read + 2), 1},
                             "expected the row of member " + std::to_string(rows_read));
        failed += rows.compare(next - 3, 3, ",ok") != 0 ? 1 : 0;
        at = next + 1;
        if (++rows_read % chunk == 0 || rows_read == count) // a whole chunk
            found.bytes = at, found.members = rows_read, found.failed = failed;
    }
    return found;
}

void journal_watch(const journal_names& names, int summary_fd, std::uint64_t bytes,
                   std::size_t members, bool made_dir) {
    copy(g_journal.dir, names.dir);
    copy(g_journal.stamp, names.stamp);
    copy(g_journal.summary, names.summary);
    copy(g_journal.trajectories, names.trajectories);
    g_journal.bytes = bytes;
    g_journal.members = members;
    g_journal.made_dir = made_dir;
    g_journal.fd = summary_fd;
    set_interrupt_hook(on_interrupt);
}

void journal_committed(std::uint64_t bytes, std::size_t members) {
    g_journal.bytes = bytes;
    g_journal.members = members;
}

void journal_not_yet() {
    set_interrupt_hook(on_interrupt_before);
}

void journal_elsewhere() {
    set_interrupt_hook(on_interrupt_quietly);
}

void journal_unwatch() {
    set_interrupt_hook(nullptr);
    g_journal.fd = -1;
}

void journal_abandon(int sig) {
    const int fd = g_journal.fd.exchange(-1);
    if (fd < 0) return;
    if (g_journal.members == 0) {
        ::unlink(g_journal.summary.data());
        ::unlink(g_journal.trajectories.data());
        ::unlink(g_journal.stamp.data());
        if (g_journal.made_dir) ::rmdir(g_journal.dir.data());
        if (sig > 0) say("rotgen: interrupted; nothing written\n");
        return;
    }
    if (::ftruncate(fd, off_t(g_journal.bytes.load())) != 0) {
        // the rows past the last whole chunk stay; --resume reads whole rows only
    }
    if (sig <= 0) return;
    char count[24];
    std::size_t n = g_journal.members, k = sizeof count;
    count[--k] = '\0';
    do
        count[--k] = char('0' + n % 10);
    while ((n /= 10) != 0 && k > 0);
    say("rotgen: interrupted; kept the journal ");
    say(g_journal.summary.data());
    say(" (");
    say(count + k);
    say(" members): add --resume to the same command to finish\n");
}

} // namespace rotgen
