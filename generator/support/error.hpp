// rotgen — user-facing errors.
//
// A user error (bad file, bad expression, bad option) is reported as one line
//   rotgen: error: FILE:LINE:COL: message
// and exit status 2. Internal failures are ordinary exceptions (exit status 1).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace rotgen {

struct source_location {
    std::string file;
    int line = 0;   // 1-based; 0 when unknown
    int column = 0; // 1-based; 0 when unknown

    source_location shifted(int columns) const {
        source_location s = *this;
        if (s.column > 0) s.column += columns;
        return s;
    }
};

// "FILE:LINE:COL" (or "FILE" / "FILE:LINE" when the finer position is unknown).
std::string to_string(const source_location& where);

class user_error : public std::runtime_error {
  public:
    user_error(source_location where, const std::string& problem)
        : std::runtime_error(problem), m_where(std::move(where)) {}
    const source_location& where() const { return m_where; }
    std::string problem() const { return what(); }
    // The whole one-line diagnostic, without the "rotgen: error: " prefix; a problem with no
    // place (an unknown command) is the problem alone.
    std::string message() const {
        if (m_where.file.empty() && m_where.line == 0) return what();
        return to_string(m_where) + ": " + what();
    }

  private:
    source_location m_where;
};

// Closest candidate by edit distance, for "did you mean 'theta'?" hints; empty if none is close.
// A candidate that differs only in case ("DOP853" for "dop853") is the closest of all.
std::string closest_name(const std::string& word, const std::vector<std::string>& candidates);

} // namespace rotgen
