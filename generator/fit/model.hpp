// rotgen fit — the model side of a fit: the free keys (`initial.<name>`, `parameters.<name>`, as
// `sweep` reads them), and the recorded columns at the measurement times with their derivatives
// with respect to the free keys.
//
// The values at the measurement times come from the integrator's dense output: the run samples at
// exactly those times (scene_spec::sample_at), not on a grid resampled afterwards.
#pragma once

#include "fit/data.hpp"
#include "run/engine.hpp"
#include "run/prepared.hpp"
#include "scene/value_keys.hpp"

#include <Eigen/Dense>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace rotgen {

struct fit_key {
    std::string key; // as written: "parameters.Ixx"
    value_key::target_t target = value_key::parameter;
    std::size_t index = 0; // angle 0..2, rate 0..2, or model parameter
    bool positive = false; // a mass: stays > 0 at every iterate
};

// The keys of `free` (comma-separated as the user wrote them), resolved against the scene;
// user_error at `where` for an unknown or repeated key, or none at all.
std::vector<fit_key> resolve_free(const scene_spec& scene, const std::vector<std::string>& free,
                                  const source_location& where);

double key_value(const member_values& values, const fit_key& key);
void set_key(member_values& values, const fit_key& key, double value);

// The run could not give the columns at these values (an unphysical inertia, a run that stopped):
// a trial step the solver must not take.
struct model_failure : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The recorded columns at the sorted distinct measurement times, and (when asked) their
// derivatives with respect to each free key.
struct model_columns {
    Eigen::MatrixXd y;               // times x columns
    std::vector<Eigen::MatrixXd> dy; // per key: times x columns (empty when not asked)
};

class fit_model {
  public:
    // Prepares the scene (holding symbolic_mutex(): Python's threads may run beside it) recording
    // the measured columns, sampled at the data's times.
    fit_model(const scene_spec& scene, const measured_data& data, std::vector<fit_key> keys,
              stage_timings& timings);
    ~fit_model(); // the prepared scene's GiNaC objects go under symbolic_mutex(), as they came
    fit_model(const fit_model&) = delete;
    fit_model& operator=(const fit_model&) = delete;

    const std::vector<fit_key>& keys() const { return m_keys; }
    const std::vector<double>& times() const { return m_times; } // sorted, distinct
    std::size_t sample_of(std::size_t row) const { return m_sample_of[row]; }
    // The run's column index of a recorded column name.
    std::size_t column(const std::string& name) const;
    const scene_spec& scene() const { return m_prepared->scene(); }
    Eigen::VectorXd start() const; // the free keys' values in the scene
    member_values values_at(const Eigen::VectorXd& x) const;

    // Throws model_failure when the run fails at x.
    model_columns evaluate(const Eigen::VectorXd& x, bool derivatives) const;
    std::size_t runs() const { return m_runs; }
    // Whether the derivatives are the sensitivities integrated with the run (every run computes
    // them then), or central differences of runs (a method that does not take them, a linear
    // rotor, a run that switches chart).
    bool sensitivities() const { return m_sensitivities; }

  private:
    run_result run_at(const member_values& v) const;
    Eigen::MatrixXd columns_of(const run_result& r) const;
    Eigen::MatrixXd columns_at(const member_values& v) const;
    model_columns differences(const member_values& v, model_columns m) const;
    model_columns integrated(const member_values& v) const;
    void without_sensitivities() const;

    std::vector<fit_key> m_keys;
    std::vector<double> m_times;
    std::vector<std::size_t> m_sample_of; // per data row: its sample (t_start is sample 0)
    mutable bool m_sensitivities = false; // false after a run switched chart
    std::vector<std::string> m_columns;
    std::vector<bool> m_needed; // per column: measured
    member_values m_base;
    std::unique_ptr<prepared_scene> m_prepared;
    mutable std::unique_ptr<prepared_scene> m_plain; // without sensitivities, after a switch
    stage_timings& m_timings;
    mutable std::size_t m_runs = 0;
};

} // namespace rotgen
