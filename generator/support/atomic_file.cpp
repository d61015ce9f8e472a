#include "support/atomic_file.hpp"

#include "support/error.hpp"
#include "support/output_paths.hpp"
#include "support/signals.hpp"
#include "support/standard_output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>

namespace rotgen {

namespace {

namespace fs = std::filesystem;

bool same_file(const std::string& a, const std::string& b) {
    struct stat sa, sb;
    return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

[[noreturn]] void cannot_write(const std::string& path, int error = errno) {
    throw user_error({path}, std::string("cannot write: ") + std::strerror(error));
}

// `text` to a device or a FIFO, opened by its own name (/dev/stdout on a pipe has no other).
void write_stream(const std::string& path, const std::string& text) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) cannot_write(path);
    for (std::size_t done = 0; done < text.size();) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int error = n < 0 ? errno : EIO;
            ::close(fd);
            cannot_write(path, error);
        }
        done += static_cast<std::size_t>(n);
    }
    if (::close(fd) != 0 && errno != EINTR) cannot_write(path);
}

} // namespace

output_set::~output_set() {
    for (const auto& f : m_files) {
        std::remove(f.temporary.c_str());
        forget_temporary(f.temporary);
    }
}

void output_set::add_file(const std::string& temporary, const std::string& target,
                          const std::string& shown) {
    m_files.push_back({temporary, target, shown});
}

void output_set::add_stream(const std::string& path, std::string text) {
    m_streams.push_back({path, std::move(text)});
}

void output_set::commit() {
    commit_streams();
    commit_files();
}

void output_set::commit_streams() {
    for (const auto& s : m_streams) {
        if (s.path == "-") {
            std::cout << s.text;
            flush_standard_output();
        } else {
            write_stream(s.path, s.text);
        }
        note_written(s.path == "-" ? "standard output" : s.path);
    }
    m_streams.clear();
}

void output_set::commit_files() {
    while (!m_files.empty()) {
        const file f = m_files.front();
        if (std::rename(f.temporary.c_str(), f.target.c_str()) != 0) cannot_write(f.shown);
        forget_temporary(f.temporary);
        m_files.erase(m_files.begin());
        note_written(f.shown);
    }
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
    m_target = follow_links(m_path);
    if (m_direct) { // written at commit (opening a FIFO waits for its reader)
        if (::access(m_path.c_str(), W_OK) != 0) cannot_write(m_path);
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
    if (m_stdout || m_direct) return m_buffer;
    return m_out;
}

void atomic_file::commit(output_set& outputs) {
    if (m_stdout || m_direct) {
        outputs.add_stream(m_stdout ? "-" : m_path, m_buffer.str());
    } else {
        m_out.close();
        if (!m_out) cannot_write(m_path);
        outputs.add_file(m_tmp, m_target, m_path);
    }
    m_done = true;
}

void atomic_file::commit() {
    output_set outputs;
    commit(outputs);
    outputs.commit();
}

void write_file_atomically(const std::string& path, const std::string& text) {
    atomic_file out(path);
    out.stream() << text;
    out.commit();
}

} // namespace rotgen
