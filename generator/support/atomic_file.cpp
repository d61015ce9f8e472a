#include "support/atomic_file.hpp"

#include "support/error.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace rotgen {

atomic_file::atomic_file(std::string path)
    : m_path(std::move(path)), m_tmp(m_path + ".tmp" + std::to_string(::getpid())) {
    m_out.open(m_tmp, std::ios::binary);
    if (!m_out) throw user_error({m_path}, std::string("cannot write: ") + std::strerror(errno));
}

atomic_file::~atomic_file() {
    if (!m_done) std::remove(m_tmp.c_str());
}

void atomic_file::commit() {
    m_out.close();
    if (!m_out || std::rename(m_tmp.c_str(), m_path.c_str()) != 0)
        throw user_error({m_path}, std::string("cannot write: ") + std::strerror(errno));
    m_done = true;
}

void write_file_atomically(const std::string& path, const std::string& text) {
    atomic_file out(path);
    out.stream() << text;
    out.commit();
}

} // namespace rotgen
