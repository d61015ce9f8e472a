// rotgen — a run's states at its samples, one after another in one buffer: a sample costs no
// allocation of its own (a member's 101 samples were 101 vectors, and their frees made glibc
// consolidate its heap at the next member's start). A run that changes chart changes the state's
// size, so each sample keeps where its state starts.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace rotgen {

class sample_states {
  public:
    void reserve(std::size_t samples, std::size_t state_size) {
        m_t.reserve(samples), m_form.reserve(samples), m_start.reserve(samples);
        m_y.reserve(samples * state_size);
    }
    // The state y at time t, integrated by form number `form` (the run's own numbering).
    void add(double t, Eigen::Ref<const Eigen::VectorXd> y, std::size_t form = 0) {
        m_t.push_back(t);
        m_form.push_back(form);
        m_start.push_back(m_y.size());
        m_y.insert(m_y.end(), y.data(), y.data() + y.size());
    }
    void pop_back() {
        m_y.resize(m_start.back());
        m_t.pop_back(), m_form.pop_back(), m_start.pop_back();
    }
    std::size_t size() const { return m_t.size(); }
    bool empty() const { return m_t.empty(); }
    double t(std::size_t k) const { return m_t[k]; }
    double last_t() const { return m_t.back(); }
    std::size_t form(std::size_t k) const { return m_form[k]; }
    Eigen::Map<const Eigen::VectorXd> y(std::size_t k) const {
        const std::size_t end = k + 1 < size() ? m_start[k + 1] : m_y.size();
        return {m_y.data() + m_start[k], static_cast<Eigen::Index>(end - m_start[k])};
    }

  private:
    std::vector<double> m_t, m_y;
    std::vector<std::size_t> m_form, m_start;
};

} // namespace rotgen
