#include "support/progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace rotgen {

progress_line::progress_line(double t_start, double t_end, bool enabled, const char* label)
    : m_start(t_start), m_end(t_end), m_label(label),
      m_enabled(enabled && ::isatty(STDERR_FILENO) == 1), m_began(clock::now()), m_last(m_began) {}

void progress_line::update(double t) {
    if (!m_enabled) return;
    const auto now = clock::now();
    const double elapsed = std::chrono::duration<double>(now - m_began).count();
    if (elapsed < 1.0 || std::chrono::duration<double>(now - m_last).count() < 0.1) return;
    m_last = now;
    const double span = m_end - m_start;
    const double done = span != 0 ? std::fabs((t - m_start) / span) : 1.0;
    char line[160];
    if (done > 0)
        std::snprintf(line, sizeof line,
                      "rotgen: %s = %.4g of %.4g (%.0f%%), %.1f s elapsed, about %.1f s to go",
                      m_label, t, m_end, 100 * done, elapsed, elapsed * (1 - done) / done);
    else
        std::snprintf(line, sizeof line, "rotgen: %s = %.4g of %.4g, %.1f s elapsed", m_label, t,
                      m_end, elapsed);
    std::fprintf(stderr, "\r%s\033[K", line);
    std::fflush(stderr);
    m_shown = true;
}

void progress_line::finish() {
    if (!m_shown) return;
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    m_shown = false;
}

} // namespace rotgen
