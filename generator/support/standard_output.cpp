#include "support/standard_output.hpp"

#include "support/error.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>

namespace rotgen {

checked_output_buffer::checked_output_buffer(int fd) : m_fd(fd) {
    setp(m_data.data(), m_data.data() + m_data.size());
}

checked_output_buffer::~checked_output_buffer() {
    drain();
}

bool checked_output_buffer::drain() {
    const char* p = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0 && m_error == 0) {
        const ssize_t n = ::write(m_fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            m_error = n < 0 ? errno : EIO;
            break;
        }
        p += n, left -= static_cast<std::size_t>(n);
    }
    setp(m_data.data(), m_data.data() + m_data.size()); // after an error: dropped
    return m_error == 0;
}

checked_output_buffer::int_type checked_output_buffer::overflow(int_type c) {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
        *pptr() = traits_type::to_char_type(c);
        pbump(1);
    }
    return traits_type::not_eof(c);
}

int checked_output_buffer::sync() {
    return drain() ? 0 : -1;
}

void flush_standard_output() {
    errno = 0;
    std::cout.flush();
    int error = 0;
    if (const auto* checked = dynamic_cast<const checked_output_buffer*>(std::cout.rdbuf()))
        error = checked->error();
    else if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout))
        error = errno != 0 ? errno : EIO; // the usual buffer: the reason when errno kept it
    if (error == 0) return;
    throw user_error({"standard output"}, std::string("cannot write: ") + std::strerror(error));
}

} // namespace rotgen
