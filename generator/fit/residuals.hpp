// rotgen fit — the residuals, model minus measured, one per measured value:
//   a scalar column       r = y_model(t) - y_measured          (an angle: wrapped into (-pi, pi])
//   the attitude q0..q3   r = rotation vector of q_measured^-1 (x) q_model (3 components, radians),
//                         the product taken with its scalar part >= 0 so that q and -q are one
//                         attitude; |r| is the angle between the two attitudes
// and their derivatives with respect to the free keys from the model's (chain rule).
#pragma once

#include "fit/data.hpp"
#include "fit/model.hpp"

#include <Eigen/Dense>

#include <array>
#include <string>
#include <vector>

namespace rotgen {

// The rotation vector (radians) of the unit quaternion q (scalar first) taken with w >= 0.
Eigen::Vector3d rotation_vector(const Eigen::Vector4d& q);

class fit_residuals {
  public:
    fit_residuals(const measured_data& data, const fit_model& model);

    // The residual columns: the measured columns, the attitude as attitude1..3.
    const std::vector<std::string>& columns() const { return m_columns; }
    // The name of each residual column's sigma: its column, or "q" for the attitude.
    const std::vector<std::string>& sigma_names() const { return m_sigma_names; }
    std::size_t size() const { return m_row.size(); }
    const measured_data& data() const { return m_data; }
    std::size_t row(std::size_t i) const { return m_row[i]; }       // the data row
    std::size_t column(std::size_t i) const { return m_column[i]; } // the residual column

    // r (size()) and, given J, dr/dkeys (size() x keys) from the model's columns.
    void compute(const model_columns& m, Eigen::VectorXd& r, Eigen::MatrixXd* J) const;

  private:
    struct source {
        std::size_t data_column;  // in measured_data::columns
        std::size_t model_column; // the run's column (q: the run's q0)
        bool angle = false, attitude = false;
    };
    void attitude(const model_columns& m, std::size_t row, std::size_t s, std::size_t q0,
                  std::size_t i, Eigen::VectorXd& r, Eigen::MatrixXd* J) const;

    const measured_data& m_data;
    const fit_model& m_model;
    std::vector<std::string> m_columns, m_sigma_names;
    std::vector<source> m_sources; // per data column
    std::vector<std::size_t> m_row, m_column, m_source;
};

} // namespace rotgen
