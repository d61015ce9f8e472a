// rotgen — the splitting methods (split2, split4, split6; runtime/steppers/splitting.hpp) in the
// run engine. They move the free body exactly and the potential by kicks, so they run the model's
// body form (quaternion and omega, y = (qw, qx, qy, qz, omega1..3)) seen as a split system: the
// torque is the body form's I omega_dot at omega = 0 (runtime/split_system.hpp), the inertia its
// principal moments (moved in the principal frame when the body axes are not principal). Records
// and invariants then come from the body form as for every method.
#pragma once

#include "run/kernels.hpp"
#include "scene/scene.hpp"

#include <Eigen/Dense>
#include <split_system.hpp>

#include <array>
#include <functional>
#include <string>
#include <variant>
#include <vector>

namespace rotgen {

// True for the method names split2, split4, split6.
bool is_split_method(const std::string& method);

// Refuses, as a user_error at the scene's integrator, a model the split methods cannot run: forces
// that depend on the rates (damping, a torque in omega or the angle rates: not kicks), or a
// principal moment that is not positive (a rotor).
void check_split_model(const scene_spec& scene, const Eigen::Matrix3d& inertia);

// The frame the split methods move the free body in: the body axes when they are principal, else
// the principal axes of the inertia stage (numeric_principal_axes), p their quaternion
// (runtime/split_system.hpp: v_body = P v_principal).
struct split_frame_values {
    bool principal = false; // the body axes are not principal: the methods rotate by p
    std::array<std::array<double, 3>, 3> tensor{};
    std::array<double, 3> moments{};
    std::array<double, 4> axes{1, 0, 0, 0};
};
split_frame_values split_frame(const Eigen::Matrix3d& inertia);

// One split method: fixed steps of the scene's `step` (symplectic, runtime/steppers/splitting.hpp),
// or, given rtol and atol, steps under error control (step doubling and the PI controller,
// runtime/steppers/split_doubling.hpp).
class split_runner {
  public:
    split_runner(const scene_spec& scene, const Eigen::Matrix3d& inertia);
    double step() const { return m_step; } // 0: error-controlled steps

    // Events (when not null) are located on the methods' continuous extension: the method run
    // from the step's start by θh, which moves the free body exactly however many turns the step
    // holds (a cubic Hermite interpolant of the quaternion across such a step would not), with the
    // search and refinement every method uses (runtime/integrate/events.hpp).
    using observer = std::function<bool(double, const Eigen::VectorXd&)>;
    integration_result<double> integrate(const loaded_system& body, double t0, Eigen::VectorXd& y,
                                         const std::vector<double>& times, const observer& observe,
                                         event_set<double, Eigen::VectorXd>* events,
                                         const error_layout& layout = {}) const;

  private:
    body_split_system<loaded_system> system(const loaded_system& body) const;

    std::string m_method;
    int m_order;
    double m_rtol, m_atol, m_step;
    std::size_t m_max_steps;
    split_frame_values m_frame;
};

} // namespace rotgen
