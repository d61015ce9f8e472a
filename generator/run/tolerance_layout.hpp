#pragma once
// What a scene's tolerance is relative to (issue 50, docs/integrators.md "What a tolerance
// means"): the error_layout of a form's state (runtime/step_control.hpp). A rate or momentum
// component (`*_dot`, `omega*`, `p_*`) belongs to the rate group 0, so it errs relative to the
// Euclidean norm of its form's rates or momenta; the components before the first of them are the
// attitude (Euler angles, the quaternion, a rotor's angles: an error of rtol radians, however far
// they have turned); any after the rates (appended to the form's state) are relative to themselves.

#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "forms/forms.hpp"
#include "scene/scene.hpp"
#include "step_control.hpp"

namespace rotgen {

// `span`: the run's |t_end - t_start|, the time the tolerance holds over (error per unit step).
inline error_layout tolerance_layout(const std::vector<state_variable>& state, double span) {
    const auto is_rate = [](const std::string& n) {
        return n.rfind("omega", 0) == 0 || n.rfind("p_", 0) == 0 ||
               (n.size() > 4 && n.compare(n.size() - 4, 4, "_dot") == 0);
    };
    error_layout layout;
    layout.span = span;
    bool rates_seen = false, rates_done = false;
    for (const state_variable& v : state) {
        const bool rate = is_rate(v.name) && !rates_done;
        if (rates_seen && !rate) rates_done = true;
        rates_seen = rates_seen || rate;
        layout.groups.push_back(rate         ? 0
                                : rates_seen ? error_layout::itself
                                             : error_layout::attitude);
    }
    return layout;
}

// The layout of `state` for a run of `scene`, over its span |t_end - t_start|: every caller (the
// engine, the lanes, the bench's generated drivers) takes the span from here.
inline error_layout tolerance_layout(const std::vector<state_variable>& state,
                                     const scene_spec& scene) {
    return tolerance_layout(state, std::abs(scene.t_end - scene.t_start));
}

template <class M, class = void> struct has_layout : std::false_type {};
template <class M>
struct has_layout<M, std::void_t<decltype(std::declval<M&>().layout)>> : std::true_type {};

// calibrate(m, layout) for a method with tolerances (the fixed-step ones have none).
template <class M> void use_layout(M& m, const error_layout& layout) {
    if constexpr (has_layout<M>::value) calibrate(m, layout);
}

} // namespace rotgen
