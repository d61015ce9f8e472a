// rotgen bench — what one configuration's run produced: the final state, the states at the
// samples (for the error, computed in long double against the reference), the work counters, the
// status and the timing.
#pragma once

#include "timing.hpp"

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

namespace rotgen::bench {

// One line of the plan: which variant (formulation + code generation), which integrator.
struct run_spec {
    int variant = 0;
    std::string peer = "rotgen"; // rotgen | odeint | cvode
    std::string method;          // rk4 dopri5 dop853 implicit_midpoint rodas4 split2 split4
                                 // split6 taylor | dopri5 rkf78 rk4 | adams bdf
    std::string scalar = "double";
    double tol = 0;  // adaptive methods (rtol = atol = tol), else 0
    double step = 0; // fixed-step methods, else 0
};

struct run_record {
    run_spec spec;
    std::string status = "ok";
    std::vector<long double> y; // the final state at the end time (in the variant's layout)
    // the state at each of the scene's sample times (driver_settings::times), delivered as
    // `rotgen simulate` delivers them (dense output, same steps), by the run that is timed
    std::vector<std::vector<long double>> samples;
    long double error = 0, orientation = 0; // the sampled error (common_state.hpp), from samples
    std::size_t rhs_evals = 0, jac_evals = 0, steps = 0;
    timed_job job; // what is timed: the same integration to the samples, from the initial state
    timing time;   // filled by the driver from job's samples
};

// Where a timed run puts the states at the samples: storage allocated once per configuration and
// filled by every run (the samples cost what they cost in `rotgen simulate`, dense output and a
// copy of the state, and no allocation), read back once as the record's samples.
template <class T> class sample_buffer {
  public:
    sample_buffer(std::size_t samples, std::size_t state_size)
        : m_values(samples * state_size), m_size(state_size) {}
    void restart() { m_next = 0; }
    template <class U> void put(const U* x) {
        if (m_next + m_size > m_values.size()) return; // more samples than asked: not stored
        for (std::size_t i = 0; i < m_size; ++i)
            m_values[m_next + i] = x[i];
        m_next += m_size;
    }
    template <class Vector> void put(const Vector& x) { put(x.data()); }
    std::vector<std::vector<long double>> rows() const {
        std::vector<std::vector<long double>> out;
        for (std::size_t at = 0; at < m_next; at += m_size)
            out.emplace_back(m_values.begin() + long(at), m_values.begin() + long(at + m_size));
        return out;
    }

  private:
    std::vector<T> m_values;
    std::size_t m_size, m_next = 0;
};

// A number as the driver writes it: 21 significant digits, "nan" for NaN.
inline std::string number(long double x) {
    if (std::isnan(x)) return "nan";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.21Lg", x);
    return buf;
}

} // namespace rotgen::bench
