#include "sweep/in_order.hpp"

#include <algorithm>
#include <exception>
#include <stdexcept>
#include <string>
#include <utility>

namespace rotgen {

in_order::in_order(std::size_t count, std::size_t window, sink out)
    : m_slots(std::max<std::size_t>(1, window)), m_ready(m_slots.size(), 0), m_count(count),
      m_window(m_slots.size()), m_out(std::move(out)) {}

bool in_order::admit(std::size_t end) {
    std::unique_lock<std::mutex> lock(m_mutex);
    m_moved.wait(lock, [&] { return m_stopped || end <= m_front + m_window; });
    return !m_stopped;
}

bool in_order::fits(std::size_t end) {
    const std::lock_guard<std::mutex> lock(m_mutex);
    return !m_stopped && end <= m_front + m_window;
}

void in_order::deliver(std::size_t m, member_outcome&& outcome) {
    const std::lock_guard<std::mutex> lock(m_mutex);
    if (m < m_front || m >= m_front + m_window)
        throw std::logic_error("sweep: member " + std::to_string(m) + " outside the window");
    m_slots[m % m_window] = std::move(outcome);
    m_ready[m % m_window] = 1;
    const std::size_t before = m_front;
    try {
        while (m_front < m_count && m_ready[m_front % m_window] && !m_stopped) {
            const std::size_t slot = m_front % m_window;
            m_ready[slot] = 0;
            member_outcome o = std::move(m_slots[slot]);
            m_slots[slot] = member_outcome{}; // its memory back now
            m_out(m_front, std::move(o));
            ++m_front;
        }
    } catch (...) {
        m_stopped = true;
        m_moved.notify_all();
        throw;
    }
    if (m_front != before) m_moved.notify_all();
}

void in_order::stop() {
    const std::lock_guard<std::mutex> lock(m_mutex);
    m_stopped = true;
    m_moved.notify_all();
}

bool in_order::stopped() {
    const std::lock_guard<std::mutex> lock(m_mutex);
    return m_stopped;
}

std::size_t in_order::done() {
    const std::lock_guard<std::mutex> lock(m_mutex);
    return m_front;
}

} // namespace rotgen
