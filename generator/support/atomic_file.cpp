#include "support/atomic_file.hpp"

#include "support/error.hpp"
#include "support/output_paths.hpp"
#include "support/signals.hpp"

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

[[noreturn]] void cannot_write(const std::string& path) {
    throw user_error({path}, std::string("cannot write: ") + std::strerror(errno));
}

} // namespace

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
    if (m_direct) { // by its own name: /dev/stdout on a pipe has no other
        m_out.open(m_path, std::ios::binary);
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
        note_written("standard output");
        m_done = true;
        return;
    }
    m_out.close();
    if (!m_out) cannot_write(m_path);
    if (!m_direct && std::rename(m_tmp.c_str(), m_target.c_str()) != 0) cannot_write(m_path);
    if (!m_direct) forget_temporary(m_tmp);
    note_written(m_path);
    m_done = true;
}

void write_file_atomically(const std::string& path, const std::string& text) {
    atomic_file out(path);
    out.stream() << text;
    out.commit();
}

} // namespace rotgen
