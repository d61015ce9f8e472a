// rotgen — sensitivities integrated with the motion: the augmented system y (+) S, S = dy/ds
// (n x k, row-major after y), Sdot = (d f/d y) S + (d f/d P) dP/ds (the variational equations,
// compiled with f as one kernel: run/variational.hpp),
// S(t0) from the exact start (run/sensitivity_start.hpp). The runtime integrates it as any system,
// so S goes through the steppers' error estimates and dense output with y.
//
// The step's error norm (runtime/step_control.hpp's error_layout): the state's components as the
// form's layout says, each entry of S relative to itself; `error_control: false` keeps S out of it
// (weight 0, as CVODES' errconS = false) and weights the state so that the norm is the state's own.
//
// A run with sensitivities keeps its chart: a run that would switch (run/engine.hpp) is refused.
#pragma once

#include "run/kernels.hpp"
#include "run/sample_states.hpp"
#include "run/sensitivity_start.hpp"
#include "support/error.hpp"

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
    // The augmented system: the form's compiled variational kernel (run/variational.hpp) with
    // this member's parameters and dP/ds, or under the Taylor method the Taylor coefficients of
    // (y, S) (run/taylor_sensitivity.hpp); refers to this object.
    loaded_system system() const;
    // The augmented state's error layout, from the form state's (above).
    error_layout layout(const error_layout& state) const;
    std::size_t keys() const { return m_keys.size(); }

    // S and the recorded columns' derivatives at the samples of `samples` that have rows (the
    // first `rows` samples, or the last of them only when !every), into `result`.
    // With result.stopped_by set, the last sample is at that terminal event: its S is the
    // event's (below).
    void record(const sample_states& samples, std::size_t rows, bool every,
                run_result& result) const;
    // At the event `which` found at (t, y): dt_e/ds = -(g_y S + g_P dP/ds) / (g_t + g_y f), and
    // the recorded columns' derivatives with the state's there, S + f dt_e/ds, into `result`.
    void record_event(std::size_t which, double t, Eigen::Ref<const Eigen::VectorXd> y,
                      run_result& result) const;

  private:
    Eigen::MatrixXd state_sensitivity(Eigen::Ref<const Eigen::VectorXd> y) const;
    // dt_e/ds (1 x k) of the event `which` at (t, y), and S moved to the event (S + f dt_e/ds).
    Eigen::RowVectorXd event_time(std::size_t which, double t, Eigen::Ref<const Eigen::VectorXd> y,
                                  Eigen::MatrixXd& S) const;
    // Every recorded column's d(column)/d(key) at (t, y) with the state's sensitivity S.
    std::vector<double> column_derivatives(double t, Eigen::Ref<const Eigen::VectorXd> y,
                                           const Eigen::MatrixXd& S) const;

    const scene_spec& m_scene;
    const compiled_form& m_cf;
    const std::vector<double> m_parameters;
    loaded_system m_base;
    std::vector<std::string> m_keys;
    start_derivatives m_start;
    std::size_t m_n = 0;
    euler_sequence m_sequence;
    bool m_sampled = false; // some column is computed at the sample, not by the record program
    std::vector<double> m_context;       // the variational kernel's v: the parameters, then dP/ds
    std::vector<double> m_taylor_values; // the Taylor method's: parameters, dP/ds inputs
};

// The refusal of a chart switch in a run with sensitivities: a user_error (the command's located
// line) that a fit tells apart, to take its Jacobian by differences of runs instead.
struct sensitivity_switch_refused : user_error {
    using user_error::user_error;
};

// Refuses the chart switch of a run with sensitivities (sensitivity_switch_refused at its
// `sensitivities:`).
[[noreturn]] void refuse_sensitivity_switch(const scene_spec& scene, double t);

} // namespace rotgen
