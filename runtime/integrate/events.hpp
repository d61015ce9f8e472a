/// \file
/// rotgen runtime — events: zeros of functions g(t, y) located on each step's dense output.
///
/// An event is a callable g(t, y) -> T with a direction and a terminal flag; an event_set holds
/// several and records where they occurred. Passed to integrate() (integrate.hpp), it is checked
/// after every accepted step:
///
///   bracket    g is evaluated at the end of each accepted step. The step is searched on its
///              interpolant (the stepper's continuous extension: DOP853 order 7, DOPRI5 order 4;
///              cubic Hermite for the others, sampling.hpp) when g changed sign over the step in
///              the direction the event watches, or when a pair of zeros could hide in it: g at
///              both ends no larger than 2 |g''| h² (|g''| the larger of the second divided
///              difference of g at the last three step ends and a quarter of the bound the last
///              search found; always in a run's first step and after a step that g varied too fast
///              to fit whole). A pair of zeros in a step needs min(|g(t)|, |g(t + h)|) <= |g''| h²
///              / 2 (Taylor about the extremum between them), so the factor 4 leaves room for a
///              changing |g''|.
///   isolate    g on the interpolant is fitted by Chebyshev interpolants on pieces of the step,
///              halved until each fit is resolved, and each fit's sign changes are proven or
///              excluded by a bound on its second derivative (event_roots.hpp). What stays
///              undecided down to pieces 64 tolerances wide (a zero where g only touches 0) is
///              noted in may_hide(): the run's summary names the interval.
///   refine     each bracket is refined on the interpolant by the Illinois variant of regula falsi
///              (Dowell & Jarratt, BIT 11 (1971) 168–174: superlinear, order 1.44, and the bracket
///              shrinks from both sides) to a bracket of width <= max(1e-14 |t|, 1e-15).
///   report     zeros in the direction of integration, with the state interpolated there (hits());
///              `rising` keeps zeros where g goes from negative to positive as t increases,
///              whichever way the run goes (a backward run meets them going from positive to
///              negative), `falling` the opposite, `both` either; a hit's sign is in t too.
///
/// Rules:
///   - a zero where g touches 0 without changing sign (an even-order zero) is not an event;
///   - an event exactly at the initial time is not reported (g(t0) = 0 sets no sign: the first
///     nonzero value does), so a run continued from an event does not report it again;
///   - chattering guard: after an event at t_e, the same event is not reported again at times
///     within 1e-12 · max(|t_e|, |t_end − t0|) of t_e (rounding in g near the zero could otherwise
///     report one crossing twice);
///   - a terminal event ends the run at its time (status::stopped_by_event, the caller's state
///     vector at the event): nothing after it is integrated, delivered to the observer or reported,
///     except the other events found at the same time (within the refinement tolerance), which are
///     reported too; samples before the event are delivered first;
///   - a NaN value of g is skipped (no sign).
/// The event_set keeps each event's last sign and last time across integrate() calls (a run
/// continued in another chart keeps its history); clear() forgets the signs, the hits and the
/// intervals noted, and keeps the last times (the guard).
///
///   event_set<double, Eigen::Vector2d> events;
///   events.add([](double, const Eigen::Vector2d& y) { return y[0]; }, event_direction::falling,
///              true, "floor");
///   auto r = integrate(sys, method, t0, y, times, observer, events);
///   for (const auto& hit : events.hits()) std::cout << events.name(hit.index) << " " << hit.t;
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "../result.hpp"
#include "event_roots.hpp"

namespace rotgen {

/// Which sign changes of g count as an event (g seen as t increases).
enum class event_direction {
    rising,  ///< g from negative to positive as t increases (in a backward run too)
    falling, ///< g from positive to negative as t increases
    both     ///< either sign change
};

/// The direction's name, "rising", "falling" or "both".
inline const char* to_string(event_direction d) {
    return d == event_direction::rising    ? "rising"
           : d == event_direction::falling ? "falling"
                                           : "both";
}

/// One event: the function g(t, y) whose zeros are located, which crossings count, whether the run
/// stops there, and a name for messages and files.
template <class T, class State> struct event {
    std::function<T(T, const State&)> g; ///< the event function g(t, y) (an event is a zero of g)
    event_direction direction = event_direction::both; ///< which sign changes count
    bool terminal = false; ///< true: the run stops at the event (status::stopped_by_event)
    std::string name;      ///< a name for messages and output files (may be empty)
};

/// One event that occurred: which, when, which way g crossed as t increases (+1 rising, −1
/// falling), the state, and the run's work up to it (the step that holds it included): what a run
/// stopped by it reports.
template <class T, class State> struct event_hit {
    std::size_t index; ///< the event's index in its event_set
    T t;               ///< the time of the zero
    int sign;          ///< +1 rising, −1 falling (as t increases)
    State y;           ///< the state at t
    step_stats work{}; ///< the run's work counters up to the event
};

/// Events of one run: zeros of each g(t, y) located on the dense output of every accepted step
/// (events.hpp's comment), the hits in time order, and whether a terminal event stopped the run.
/// \tparam T the scalar type; \tparam State the state vector type passed to g.
template <class T, class State> class event_set {
  public:
    using function =
        std::function<T(T, const State&)>; ///< the type of an event function, g(t, y) -> T

    std::size_t max_pieces = 4096; ///< the most pieces one step's search fits, per event

    /// Adds an event; returns its index.
    std::size_t add(event<T, State> e) {
        m_events.push_back(std::move(e));
        m_track.push_back({});
        return m_events.size() - 1;
    }
    /// Adds an event g with direction d, terminal flag and name; returns its index.
    std::size_t add(function g, event_direction d = event_direction::both, bool terminal = false,
                    std::string name = "") {
        return add({std::move(g), d, terminal, std::move(name)});
    }

    /// The number of events.
    std::size_t size() const { return m_events.size(); }
    /// Event i.
    const event<T, State>& operator[](std::size_t i) const { return m_events[i]; }
    /// The name of event i.
    const std::string& name(std::size_t i) const { return m_events[i].name; }
    /// The event functions may be exchanged between runs (the same zero in another state layout).
    void set_function(std::size_t i, function g) { m_events[i].g = std::move(g); }

    /// The events that occurred in the last run, in time order.
    const std::vector<event_hit<T, State>>& hits() const { return m_hits; }
    /// The terminal event that ended the last run, if one did.
    bool stopped() const { return m_stopped; }
    /// The index of the terminal event that ended the last run (valid when stopped()).
    std::size_t stopped_by() const { return m_stopped_by; }
    /// The number of steps whose interpolant was searched for zeros (a step excluded by the sign
    /// of g and a bound is not searched).
    std::size_t steps_searched() const { return m_searched; }

    /// Intervals of t where a pair of zeros of event `index` may hide: the search could neither
    /// find a sign change there nor exclude one (a zero where g only touches 0, or g not resolved).
    struct hidden {
        std::size_t index; ///< the event
        T from;            ///< the interval of t: its start
        T to;              ///< and its end
    };
    /// The intervals where a pair of zeros may hide, from the last run.
    const std::vector<hidden>& may_hide() const { return m_hidden; }

    /// Forgets the hits and the signs; keeps each event's last time, so that a run continued from
    /// an event does not report it again whatever the sign of g's residue there (the guard).
    void clear() {
        m_hits.clear();
        m_hidden.clear();
        m_stopped = false;
        for (auto& k : m_track) {
            const T last = k.last_fire;
            const bool fired = k.fired;
            k = {};
            k.last_fire = last, k.fired = fired;
        }
    }

    // ---- used by the driver (integrate/step_end.hpp) ----

    /// A run starts at (t0, y0) towards t_end.
    void begin(T t0, const State& y0, T t_end) {
        using std::abs;
        m_dir = t_end >= t0 ? T(1) : T(-1);
        m_span = abs(t_end - t0);
        m_stopped = false;
        m_first_step = true;
        m_y = y0;
        for (std::size_t i = 0; i < size(); ++i) {
            track& k = m_track[i];
            k.g0 = m_events[i].g(t0, y0);
            k.t0 = t0;
            k.have_prev = false;
            if (sign_of(k.g0) != 0) k.sign = sign_of(k.g0);
        }
    }

    /// After an accepted step [t, t1] with the new state y1: g at t1, and whether the step must be
    /// searched on its interpolant (a sign change, or a pair of zeros could hide in it).
    bool check_step(T t, T t1, const State& y1) {
        bool search = m_first_step;
        m_first_step = false;
        for (std::size_t i = 0; i < size(); ++i) {
            track& k = m_track[i];
            k.g1 = m_events[i].g(t1, y1);
            search = search || may_hold_zero(k, t1 - t, m_events[i].direction);
        }
        return search;
    }

    /// Searches the step [t, t + h] on the interpolant `interp(theta, State& out)`, theta in
    /// [0, 1], and lists its zeros in time order (found()); where a pair of zeros may hide
    /// undecided, notes the interval (may_hide()).
    template <class Interp> void search(T t, T h, const Interp& interp) {
        using roots = detail::event_roots<T>;
        ++m_searched;
        m_found.clear();
        m_nodes.resize(static_cast<std::size_t>(roots::n + 1) * size());
        for (std::size_t i = 0; i < size(); ++i)
            node(0, i) = m_track[i].g0, node(roots::n, i) = m_track[i].g1;
        for (int j = 1; j < roots::n; ++j) {
            const T theta = roots::node(T(0), T(1), j);
            interp(theta, m_y);
            for (std::size_t i = 0; i < size(); ++i)
                node(j, i) = m_events[i].g(t + theta * h, m_y);
        }
        for (std::size_t i = 0; i < size(); ++i)
            search_event(i, t, h, interp);
        std::stable_sort(m_found.begin(), m_found.end(),
                         [&](const zero& a, const zero& b) { return m_dir * (a.t - b.t) < T(0); });
    }

    /// A zero found on the current step (driver's use: event_step.hpp).
    struct zero {
        std::size_t index; ///< the event
        T t;               ///< where
        int sign;          ///< +1 rising, −1 falling
    };
    /// The zeros of the current step, in the run's time order (driver's use).
    const std::vector<zero>& found() const { return m_found; }

    /// Reports a found zero with the state there and the run's work so far; false when it is
    /// terminal.
    bool report(const zero& z, const State& y, const step_stats& work = {}) {
        m_hits.push_back({z.index, z.t, z.sign, y, work});
        m_track[z.index].last_fire = z.t;
        m_track[z.index].fired = true;
        if (!m_events[z.index].terminal) return true;
        m_stopped = true;
        m_stopped_by = z.index;
        return false;
    }

    /// The refinement tolerance at t: max(1e-14 |t|, 1e-15).
    static T tolerance(T t) {
        using std::abs;
        return std::max(T(1e-14) * abs(t), T(1e-15));
    }

    /// The step is done: g at its end becomes g at the next step's start.
    void end_step(T t1) {
        for (auto& k : m_track) {
            if (sign_of(k.g1) != 0) k.sign = sign_of(k.g1);
            k.gm = k.g0, k.tm = k.t0, k.have_prev = true;
            k.g0 = k.g1, k.t0 = t1;
        }
    }

  private:
    struct track {
        T g0 = T(0), g1 = T(0), t0 = T(0); // g at the step's start and end
        T gm = T(0), tm = T(0);            // g at the previous step's start
        bool have_prev = false;
        int sign = 0; // last nonzero sign of g seen
        T last_fire = T(0);
        bool fired = false;
        T curvature = T(0);      // max |g''| on the last searched step, as its fits bound it
        bool unresolved = false; // that step needed more than one fit: g varies faster than steps
    };

    static int sign_of(T v) { return v > T(0) ? 1 : v < T(0) ? -1 : 0; }

    T& node(int j, std::size_t i) { return m_nodes[static_cast<std::size_t>(j) * size() + i]; }

    /// A sign change over the step in the direction watched; or a zero g could reach inside the
    /// step if |g''| were as large as K = 16 |g''|, |g''| the larger of the divided difference's
    /// and the last search's bound; or the last search needed more than one fit. Given K: |g| at
    /// both ends within K h² / 8 (a parabola of curvature K through the ends dips that far), and
    /// the lowest point of that parabola inside the step and at or below zero; for a change the
    /// direction filter drops (more zeros, one of them watched, could hide beside it), also g not
    /// proven monotone (|g1 - g0| > K h²: g' keeps its sign).
    bool may_hold_zero(const track& k, T h, event_direction d) const {
        using std::abs;
        using std::isnan;
        if (isnan(k.g1) || isnan(k.g0)) return false;
        const int s1 = sign_of(k.g1);
        const bool change = s1 != 0 && k.sign != 0 && s1 != k.sign;
        if (change &&
            (d == event_direction::both || (d == event_direction::rising) == (s1 * m_dir > 0)))
            return true;
        if (!k.have_prev || k.unresolved) return true;
        const T hm = k.t0 - k.tm;
        const T g2 = T(2) * ((k.g1 - k.g0) / h - (k.g0 - k.gm) / hm) / (h + hm); // ≈ g''
        const T K = T(16) * std::max(abs(g2), k.curvature / T(4));
        const T a0 = abs(k.g0), a1 = abs(k.g1);
        if (std::min(a0, a1) > K * h * h / T(8)) return false;
        if (change) return abs(k.g1 - k.g0) <= K * h * h;
        return parabola_reaches_zero(a0, a1, K, h);
    }

    /// Whether p(x) = a0 + (a1 - a0) x/h - K x (h - x)/2, a0, a1 >= 0 (the lowest g with |g''| <= K
    /// and these end values can be), is <= 0 somewhere in [0, h].
    static bool parabola_reaches_zero(T a0, T a1, T K, T h) {
        if (a0 == T(0) || a1 == T(0)) return true;
        if (!(K > T(0))) return false;              // a straight line between positive ends
        const T x = h / T(2) - (a1 - a0) / (K * h); // p's vertex
        if (!(x > T(0) && x < h)) return false;
        return a0 + (a1 - a0) * x / h - K * x * (h - x) / T(2) <= T(0);
    }

    /// g of event i at t + theta h on the interpolant
    template <class Interp> T g_at(std::size_t i, T t, T h, T theta, const Interp& interp) {
        interp(theta, m_y);
        return m_events[i].g(t + theta * h, m_y);
    }

    /// The zeros of event i on the step: the sign changes between the points event_roots leaves
    /// (each confirmed on g itself and refined there); the sign before the step is the last
    /// nonzero one.
    template <class Interp> void search_event(std::size_t i, T t, T h, const Interp& interp) {
        using std::abs;
        std::array<T, detail::event_roots<T>::n + 1> f{};
        for (int j = 0; j <= detail::event_roots<T>::n; ++j)
            f[static_cast<std::size_t>(j)] = node(j, i);
        const T min_width = T(64) * tolerance(abs(t) + abs(h)) / abs(h);
        m_roots.run(
            f, [&](T theta) { return g_at(i, t, h, theta, interp); }, min_width, max_pieces);
        track& k = m_track[i];
        k.curvature = m_roots.curvature() / (h * h);
        k.unresolved = m_roots.pieces() > 1;
        for (const auto& u : m_roots.undecided())
            note_hidden(i, t + u.from * h, t + u.to * h);
        const auto& p = m_roots.points();
        int before = k.sign;
        for (std::size_t j = 1; j < p.size(); ++j) {
            const int s = sign_of(p[j].value);
            if (s == 0 || s == before) continue;
            if (before != 0) bracket(i, t, h, j, interp);
            before = s;
        }
    }

    /// p changes sign between points j − 1 and j: the zero of g there (or between the points
    /// beside them), refined on the interpolant.
    template <class Interp>
    void bracket(std::size_t i, T t, T h, std::size_t j, const Interp& interp) {
        const auto& p = m_roots.points();
        const int s = sign_of(p[j].value);
        const auto g = [&](std::size_t q) {
            return q == 0              ? m_track[i].g0
                   : q + 1 == p.size() ? m_track[i].g1
                                       : g_at(i, t, h, p[q].theta, interp);
        };
        std::size_t a = j - 1, b = j;
        T ga = g(a), gb = g(b);
        if (ga != T(0) && sign_of(ga) != -sign_of(gb)) { // p's error moved it: one point wider
            a = a > 0 ? a - 1 : a, b = b + 1 < p.size() ? b + 1 : b;
            ga = g(a), gb = g(b);
        }
        const T ta = t + p[a].theta * h, tb = t + p[b].theta * h;
        if (ga != T(0) && sign_of(ga) != -sign_of(gb)) return note_hidden(i, ta, tb);
        const int rising = m_dir > T(0) ? s : -s;           // the sign as t increases
        if (dropped(m_events[i].direction, rising)) return; // not refined: the filter drops it
        accept_zero(i, ga == T(0) ? ta : refine(i, ta, ga, tb, gb, t, h, interp), rising);
    }

    /// Whether the direction filter drops a zero where g's sign becomes `s` as t increases.
    static bool dropped(event_direction d, int s) {
        return (d == event_direction::rising && s < 0) || (d == event_direction::falling && s > 0);
    }

    void note_hidden(std::size_t i, T from, T to) {
        if (from > to) std::swap(from, to);
        // one with the last when the gap between them is no wider than they are together
        if (!m_hidden.empty() && m_hidden.back().index == i &&
            std::max(from - m_hidden.back().to, m_hidden.back().from - to) <=
                (to - from) + (m_hidden.back().to - m_hidden.back().from)) {
            m_hidden.back().from = std::min(m_hidden.back().from, from);
            m_hidden.back().to = std::max(m_hidden.back().to, to);
            return;
        }
        m_hidden.push_back({i, from, to});
    }

    /// Keeps a zero unless the direction filter or the chattering guard drops it.
    void accept_zero(std::size_t i, T tz, int s) {
        using std::abs;
        const track& k = m_track[i];
        if (dropped(m_events[i].direction, s)) return;
        const T guard = T(1e-12) * std::max(abs(k.last_fire), m_span);
        for (const zero& z : m_found) // zeros of this step not yet reported
            if (z.index == i && abs(z.t - tz) <= guard) return;
        if (k.fired && abs(tz - k.last_fire) <= guard) return;
        m_found.push_back({i, tz, s});
    }

    /// Illinois: regula falsi on [a, b] (g(a) g(b) < 0); when the same end is kept twice in a row
    /// its value is halved, so that both ends move. Stops at a bracket no wider than tolerance().
    template <class Interp>
    T refine(std::size_t i, T a, T ga, T b, T gb, T t, T h, const Interp& interp) {
        using std::abs;
        int kept = 0; // +1: a was kept last time, −1: b
        T c = a;
        for (int it = 0; it < 200 && abs(b - a) > tolerance(c); ++it) {
            c = (a * gb - b * ga) / (gb - ga);
            if (!(std::min(a, b) < c && c < std::max(a, b))) c = a + (b - a) / T(2);
            interp((c - t) / h, m_y);
            const T gc = m_events[i].g(c, m_y);
            if (gc == T(0) || !(gc == gc)) break;
            if ((gc > T(0)) == (gb > T(0))) {
                b = c, gb = gc;
                if (kept == 1) ga /= T(2);
                kept = 1;
            } else {
                a = c, ga = gc;
                if (kept == -1) gb /= T(2);
                kept = -1;
            }
        }
        return c;
    }

    std::vector<event<T, State>> m_events;
    std::vector<track> m_track;
    std::vector<T> m_nodes;
    std::vector<zero> m_found;
    std::vector<hidden> m_hidden;
    detail::event_roots<T> m_roots;
    std::vector<event_hit<T, State>> m_hits;
    State m_y;
    T m_dir = T(1), m_span = T(0);
    bool m_first_step = true, m_stopped = false;
    std::size_t m_stopped_by = 0, m_searched = 0;
};

} // namespace rotgen
