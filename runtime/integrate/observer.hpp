/// \file
/// rotgen runtime — observers: what integrate() calls at each sample, and how to combine them.
///
/// An observer is a callable observer(T t, const state_vector<T, S>& y), called once per sample in
/// order. It returns either
///   void   the run goes on to the end time, or
///   bool   true: go on; false: stop after this sample. integrate() then returns with
///          status::stopped_by_observer, result.t = the time of that sample and the caller's state
///          vector holding the state delivered at it (interpolated when the sample lies inside a
///          step), so that a run can be continued from there — no exceptions needed.
///
///   observe_all(o1, o2, ...)   one observer calling each of o1, o2, ... in order at every sample
///                              (all of them, also after one asked to stop); it asks to stop when
///                              any of them returned false. Arguments are held by value: pass
///                              std::ref(o) to keep a stateful observer (a monitor) outside.
#pragma once

#include <functional>
#include <tuple>
#include <type_traits>
#include <utility>

namespace rotgen {

namespace detail {

/// Calls the observer; true when the run goes on (void observers always go on).
template <class Observer, class T, class V> bool notify(Observer& observer, T t, const V& y) {
    if constexpr (std::is_void_v<decltype(observer(t, y))>) {
        observer(t, y);
        return true;
    } else {
        return static_cast<bool>(observer(t, y));
    }
}

} // namespace detail

/// Several observers as one (observe_all()): each is called at every sample, in order; the run
/// goes on only while none returns false.
template <class... Observers> class observer_group {
  public:
    /// The observers, held by value (pass std::ref to keep one outside).
    explicit observer_group(Observers... observers) : m_observers(std::move(observers)...) {}

    /// Calls every observer with (t, y); false when any of them returned false.
    template <class T, class V> bool operator()(T t, const V& y) {
        return std::apply(
            [&](auto&... o) {
                bool go_on = true;
                ((go_on = detail::notify(unwrap(o), t, y) && go_on), ...);
                return go_on;
            },
            m_observers);
    }

  private:
    template <class O> static O& unwrap(O& o) { return o; }
    template <class O> static O& unwrap(std::reference_wrapper<O> o) { return o.get(); }

    std::tuple<Observers...> m_observers;
};

/// Combines observers into one (observer_group); wrap an observer in std::ref to read it after
/// the run.
template <class... Observers>
observer_group<std::decay_t<Observers>...> observe_all(Observers&&... o) {
    return observer_group<std::decay_t<Observers>...>(std::forward<Observers>(o)...);
}

} // namespace rotgen
