// rotgen — the splitting methods (split2, split4, split6; runtime/steppers/splitting.hpp) in the
// run engine. They move the free body exactly and the potential by kicks, so they run the model's
// body form (quaternion and omega, y = (qw, qx, qy, qz, omega1..3)) seen as a split system: the
// torque is the body form's I omega_dot at omega = 0 (runtime/split_system.hpp), the inertia its
// principal moments. Records and invariants then come from the body form as for every method.
#pragma once

#include "run/kernels.hpp"
#include "scene/scene.hpp"

#include <Eigen/Dense>

#include <array>
#include <functional>
#include <string>
#include <variant>
#include <vector>

namespace rotgen {

// True for the method names split2, split4, split6.
bool is_split_method(const std::string& method);

// Refuses, as a user_error at the scene's integrator, a model the split methods cannot run: forces
// that depend on the rates (damping, a torque in omega or the angle rates: not kicks), an inertia
// whose body axes are not principal axes, or a moment that is not positive (a rotor).
void check_split_model(const scene_spec& scene, const Eigen::Matrix3d& inertia);

// One split method with its step: the scene's `step`, or the rule of runtime/split_step_rule.hpp
// from its rtol at the initial state y0.
class split_runner {
  public:
    split_runner(const scene_spec& scene, const Eigen::Matrix3d& inertia);
    // Fixes the step (from the rule when the scene gives rtol) for the system at (t0, y0).
    void choose_step(const loaded_system& body, double t0, const Eigen::VectorXd& y0, double span);
    double step() const { return m_step; }

    using observer = std::function<bool(double, const Eigen::VectorXd&)>;
    integration_result<double> integrate(const loaded_system& body, double t0, Eigen::VectorXd& y,
                                         const std::vector<double>& times,
                                         const observer& observe) const;

  private:
    std::string m_method;
    int m_order;
    double m_rtol, m_step;
    std::size_t m_max_steps;
    std::array<double, 3> m_moments;
};

} // namespace rotgen
