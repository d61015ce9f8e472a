/// \file
/// rotgen runtime — the events of an accepted step (events.hpp): g at the step's end, the search on
/// the interpolant when the step may hold a zero, and the zeros reported in time order, each after
/// the samples before it. Called by end_of_step (step_end.hpp) when integrate() was given events.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>

#include "../combine.hpp"
#include "../result.hpp"
#include "events.hpp"
#include "messages.hpp"
#include "sampling.hpp"

namespace rotgen::detail {

/// A sampler (sampling.hpp) that also watches an event_set.
template <class Base, class Events> class event_sampler : public Base {
  public:
    static constexpr bool has_events = true;
    event_sampler(const Base& base, Events& events) : Base(base), m_events(&events) {}
    Events& events() const { return *m_events; }

  private:
    Events* m_events;
};

template <class T> ROTGEN_COLD std::string event_message(const std::string& name, T t) {
    return "stopped by the terminal event" + (name.empty() ? std::string() : " '" + name + "'") +
           " at t = " + format_time(t);
}

/// Accepts the step [t, t_next] of size h (preparing the interpolant if samples or a search need
/// it) and reports its events. False when the run ends in the step: the observer asked to stop at a
/// sample before an event (status::stopped_by_observer), or a terminal event
/// (status::stopped_by_event); `t` and `y_now` are then at that sample or event.
template <class S, class St, class Sampler, class T, class V>
ROTGEN_ALWAYS_INLINE bool step_events(const S& sys, St& st, step_stats& stats, Sampler& samples,
                                      bool need_dense, bool& f_ok, T& t, T t_next, T h, V& y_now,
                                      V& ys, integration_result<T>& res) {
    auto& events = samples.events();
    assign(ys, st.y_new());
    const bool search = events.check_step(t, t_next, static_cast<const V&>(ys));
    f_ok = st.accept(sys, stats, need_dense || search);
    if (!search) {
        events.end_step(t_next);
        return true;
    }
    events.search(t, h, [&](T theta, V& out) { interpolate(st, theta, out); });
    const auto& found = events.found();
    for (std::size_t z = 0; z < found.size(); ++z) {
        const T tz = found[z].t;
        if (need_dense && !samples.deliver_inside(st, t, h, tz, ys)) {
            y_now = ys;
            t = samples.stop_time();
            res.code = status::stopped_by_observer;
            res.message = stopped_message(t);
            return false;
        }
        interpolate(st, (tz - t) / h, ys);
        if (events.report(found[z], static_cast<const V&>(ys), stats)) continue;
        y_now = ys; // a terminal event: the others at the same time are reported too
        using std::abs;
        for (std::size_t w = z + 1;
             w < found.size() && abs(found[w].t - tz) <= events.tolerance(tz); ++w) {
            interpolate(st, (found[w].t - t) / h, ys);
            events.report(found[w], static_cast<const V&>(ys), stats);
        }
        t = tz;
        res.code = status::stopped_by_event;
        res.message = event_message(events.name(found[z].index), tz);
        return false;
    }
    events.end_step(t_next);
    return true;
}

} // namespace rotgen::detail
