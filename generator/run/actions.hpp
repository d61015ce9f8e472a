// rotgen — events that act during a run (scene/event_actions.hpp): their counts, the times of the
// time events (`every`), and the state an action leaves.
//
// The engine (run/engine.cpp) integrates in segments between actions: an acting event (or a stop
// with `after`) is terminal for the runtime, so the segment ends at its zero; a time event ends the
// segment at its time exactly (the last step lands there). The action forms the new state as
// `initial:` forms a start, from the attitude and body omega before it:
//   attitude    set by one way (angles, some of them: the others kept; q0..q3, some of them:
//               the others kept, the whole then unit to 1e-6 and normalised; A, orthonormal to
//               1e-9), else kept;
//   velocity    set by one way (rates q_dot: omega = J(q) q_dot at the new attitude, 5.30; momenta
//               p: omega = I^-1 J^-T p; body omega; space omega: omega = A omega_space), the
//               components not set kept in that way, else body omega kept;
//   impulse     omega += I^-1 J (body axes: Delta L = J); impulse_space: J = A J_space;
//   parameters  parameters.<name> set (the form's parameter values are formed anew).
// Values are expressions evaluated (GiNaC, under symbolic_mutex(), in double) over the state
// before the event, t and the parameters before it. The new state then starts a fresh
// integration (new first step, fresh dense output). Events are zeros along the continuous
// motion: a jump of an event's g across 0 made by an action is not an event, and a g that is zero
// right after the action is not reported at that time again (runtime/integrate/events.hpp).
#pragma once

#include "run/kinematics.hpp"
#include "scene/scene.hpp"

#include <euler_sequence.hpp> // runtime

#include <Eigen/Dense>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rotgen {

// The state at an action: the form's state y with f(t, y) (the Euler-angle forms' rates).
struct action_state {
    form_kind form;
    double t;
    const Eigen::VectorXd& y;
    const Eigen::VectorXd& dydt;
};

// The state after an action, or why the action could not form one (a located message: the run
// stops there).
struct action_outcome {
    initial_kinematics k;
    std::string error;
};

class run_actions {
  public:
    // The scene's events, at a member's parameter values (the periods of `every`). Throws
    // user_error for actions in a backward run.
    run_actions(const scene_spec& scene, const euler_sequence& sequence,
                const std::vector<long double>& model_parameters);

    // Whether the runtime stops at event i (an action or a stop: the engine decides there).
    bool terminal(std::size_t i) const;
    // Notes an occurrence of event i; whether it counts (from its `after`-th on).
    bool occurs(std::size_t i);
    // The first time event after t, before t_end: its time and index.
    std::optional<std::pair<double, std::size_t>> next_time(double t, double t_end) const;
    // How many times event i acted (impulse, set) or occurred counted (record, stop).
    std::size_t count(std::size_t i) const { return m_counted[i]; }

    // The action of event i at `s`; `parameters` (the model's, in model order) are updated.
    action_outcome apply(std::size_t i, const action_state& s, const Eigen::Matrix3d& inertia,
                         std::vector<long double>& parameters) const;

  private:
    const scene_spec& m_scene;
    const euler_sequence& m_sequence;
    std::vector<double> m_period; // of each time event (0: not one)
    std::vector<std::size_t> m_seen, m_counted;
};

// Whether a scene's events need the engine's segments (an action, `every` or `after`).
bool has_actions(const scene_spec& scene);

} // namespace rotgen
