// rotgen — sensitivities integrated with the motion: the augmented system y (+) S, S = dy/ds
// (n x k, row-major after y), Sdot = (d f/d y) S + (d f/d P) dP/ds (the variational equations),
// S(t0) from the exact start (run/sensitivity_start.hpp). The runtime integrates it as any system,
// so S goes through the steppers' error estimates and dense output with y.
//
// `error_control: false` keeps S out of the error norm (the state alone, as CVODES' errconS =
// false) without a change to the runtime: the run integrates c S with c = 2^-300, whose errors
// are then negligible against atol, and scales rtol and atol by sqrt(n / (n + n k)), so that the
// RMS norm over the augmented state equals the state's own.
//
// A run with sensitivities keeps its chart: a run that would switch (run/engine.hpp) is refused.
#pragma once

#include "run/kernels.hpp"
#include "run/sample_states.hpp"
#include "run/sensitivity_start.hpp"

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace rotgen {

class prepared_scene;
struct member_values;
struct run_result;

class sensitivity_run {
  public:
    // At the member's start k0 in the form `cf` with its parameter values `parameters`. Takes
    // symbolic_mutex() for the start's derivatives.
    sensitivity_run(const prepared_scene& prepared, const member_values& values,
                    const compiled_form& cf, const std::vector<double>& parameters,
                    const initial_kinematics& k0);
    sensitivity_run(const sensitivity_run&) = delete;
    sensitivity_run& operator=(const sensitivity_run&) = delete;

    // The augmented state at t0: y0, then S(t0) (scaled).
    Eigen::VectorXd augmented(const Eigen::VectorXd& y0) const;
    // The augmented system (refers to this object).
    loaded_system system() const;
    // The factor on rtol and atol (error_control false; else 1) for a state of size n.
    static double tolerance_factor(const scene_spec& scene, std::size_t n);
    std::size_t keys() const { return m_keys.size(); }

    // S and the recorded columns' derivatives at the samples of `samples` that have rows (the
    // first `rows` samples, or the last of them only when !every), into `result`.
    void record(const sample_states& samples, std::size_t rows, bool every,
                run_result& result) const;

  private:
    static void rhs(const double* self, double t, const double* y, double* dydt);
    Eigen::MatrixXd state_sensitivity(Eigen::Ref<const Eigen::VectorXd> y) const;

    const scene_spec& m_scene;
    const compiled_form& m_cf;
    const std::vector<double> m_parameters;
    loaded_system m_base;
    std::vector<std::string> m_keys;
    start_derivatives m_start;
    double m_scale = 1;
    std::size_t m_n = 0;
    mutable Eigen::MatrixXd m_jacobian, m_dfdp; // scratch (row-major data), one run at a time
    mutable std::vector<double> m_scratch;
};

// Refuses the chart switch of a run with sensitivities (user_error at its `sensitivities:`).
[[noreturn]] void refuse_sensitivity_switch(const scene_spec& scene, double t);

} // namespace rotgen
