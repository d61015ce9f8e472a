// rotgen sweep — members' outcomes, finished in any order, handed on in member order through a
// bounded window: a member m is admitted (may start) only when every member before m - window
// has been handed on, so that at most `window` outcomes wait in memory however many threads and
// ranks run them and however long one member takes. The outcome of member m waits in its slot
// (m % window) until every member before it is done; then the one that completes the prefix hands
// them on, in order, to the sink (the files' writer), one thread at a time.
#pragma once

#include "sweep/outcome.hpp"

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <vector>

namespace rotgen {

class in_order {
  public:
    using sink = std::function<void(std::size_t member, member_outcome&& outcome)>;
    in_order(std::size_t count, std::size_t window, sink out);

    // Waits until members before `end` fit the window; false if stopped (start nothing then).
    bool admit(std::size_t end);
    // Whether members before `end` fit the window now (does not wait).
    bool fits(std::size_t end);
    // Member m's outcome; hands on the prefix it completes. A sink that throws stops the window
    // and the exception goes on to the caller.
    void deliver(std::size_t m, member_outcome&& outcome);
    // Wakes every admit() with false, and admits nothing more.
    void stop();
    bool stopped();
    std::size_t done(); // members handed on
    std::size_t window() const { return m_window; }

  private:
    std::mutex m_mutex;
    std::condition_variable m_moved;
    std::vector<member_outcome> m_slots;
    std::vector<char> m_ready;
    std::size_t m_count, m_window, m_front = 0;
    bool m_stopped = false;
    sink m_out;
};

} // namespace rotgen
