#include "support/atomic_file.hpp"

#include "support/error.hpp"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>

namespace rotgen {

namespace {

namespace fs = std::filesystem;

// The registry the signal handler reads: fixed storage, no allocation in the handler.
constexpr std::size_t max_temporaries = 64, max_path = 4096;
std::array<std::array<char, max_path>, max_temporaries> g_temporaries{};
std::array<volatile sig_atomic_t, max_temporaries> g_used{};
void (*volatile g_hook)(int) = nullptr; // set_interrupt_hook

extern "C" void on_signal(int sig) {
    if (void (*hook)(int) = g_hook) hook(sig);
    for (std::size_t i = 0; i < max_temporaries; ++i)
        if (g_used[i]) ::unlink(g_temporaries[i].data());
    ::_exit(128 + sig);
}

bool same_file(const std::string& a, const std::string& b) {
    struct stat sa, sb;
    return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

// The file a path names after following symlinks, also when the last one dangles (it is then
// created): the link stays a link.
std::string resolve_links(const std::string& path) {
    fs::path p = path;
    std::error_code ec;
    for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
        const fs::path target = fs::read_symlink(p, ec);
        if (ec) break;
        p = target.is_absolute() ? target : p.parent_path() / target;
    }
    return p.string();
}

[[noreturn]] void cannot_write(const std::string& path) {
    throw user_error({path}, std::string("cannot write: ") + std::strerror(errno));
}

} // namespace

void register_temporary(const std::string& path) {
    if (path.size() >= max_path) return;
    for (std::size_t i = 0; i < max_temporaries; ++i)
        if (!g_used[i]) {
            std::memcpy(g_temporaries[i].data(), path.c_str(), path.size() + 1);
            g_used[i] = 1;
            return;
        }
}

void forget_temporary(const std::string& path) {
    for (std::size_t i = 0; i < max_temporaries; ++i)
        if (g_used[i] && path == g_temporaries[i].data()) g_used[i] = 0;
}

void set_interrupt_hook(void (*hook)(int)) {
    g_hook = hook;
}

void remove_temporaries_on_signal() {
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    ::sigaction(SIGINT, &sa, nullptr);
    ::sigaction(SIGTERM, &sa, nullptr);
}

atomic_file::atomic_file(std::string path, const std::vector<std::string>& inputs)
    : m_path(std::move(path)) {
    if (m_path == "-") {
        m_stdout = true;
        return;
    }
    for (const auto& in : inputs)
        if (same_file(m_path, in))
            throw user_error({m_path},
                             "refusing to write over '" + in + "', a file this command reads");
    std::error_code ec;
    const fs::file_status st = fs::status(m_path, ec); // follows symlinks
    m_direct = fs::exists(st) && !fs::is_regular_file(st);
    m_target = resolve_links(m_path);
    if (m_direct) {
        m_out.open(m_target, std::ios::binary);
        if (!m_out) cannot_write(m_path);
        return;
    }
    m_tmp = m_target + ".tmp" + std::to_string(::getpid());
    register_temporary(m_tmp);
    m_out.open(m_tmp, std::ios::binary);
    if (!m_out) {
        forget_temporary(m_tmp);
        cannot_write(m_path);
    }
}

atomic_file::~atomic_file() {
    if (m_done || m_tmp.empty()) return;
    m_out.close();
    std::remove(m_tmp.c_str());
    forget_temporary(m_tmp);
}

std::ostream& atomic_file::stream() {
    if (m_stdout) return m_buffer;
    return m_out;
}

void atomic_file::commit() {
    if (m_stdout) {
        std::cout << m_buffer.str() << std::flush;
        m_done = true;
        return;
    }
    m_out.close();
    if (!m_out) cannot_write(m_path);
    if (!m_direct && std::rename(m_tmp.c_str(), m_target.c_str()) != 0) cannot_write(m_path);
    if (!m_direct) forget_temporary(m_tmp);
    m_done = true;
}

void write_file_atomically(const std::string& path, const std::string& text) {
    atomic_file out(path);
    out.stream() << text;
    out.commit();
}

} // namespace rotgen
