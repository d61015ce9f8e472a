// rotgen — a one-line progress indicator on standard error, for runs long enough to wait for:
//
//   rotgen: t = 41.2 of 100 (41%), 2.1 s elapsed, about 3.0 s to go
//
// Shown only when standard error is a terminal and the run has lasted about a second; at most
// 10 updates a second; erased when the run ends (finish() or the destructor).
#pragma once

#include <chrono>
#include <string>

namespace rotgen {

class progress_line {
  public:
    // `enabled` false (e.g. --quiet) or standard error not a terminal: shows nothing. `label`
    // names what is counted ("t = 41.2 of 100", "members = 96 of 1024").
    progress_line(double t_start, double t_end, bool enabled, const char* label = "t");
    progress_line(const progress_line&) = delete;
    progress_line& operator=(const progress_line&) = delete;
    ~progress_line() { finish(); }

    void update(double t);
    void finish(); // erases the line

  private:
    using clock = std::chrono::steady_clock;
    double m_start, m_end;
    const char* m_label;
    bool m_enabled, m_shown = false;
    clock::time_point m_began, m_last;
};

} // namespace rotgen
