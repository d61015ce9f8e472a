// rotgen fit — the weighted least-squares problem and its solution with Eigen's Levenberg–
// Marquardt (unsupported/Eigen/NonLinearOptimization: MINPACK's lmder, with its scaling of the
// parameters by the Jacobian's column norms). The Jacobian comes from the model (fit/model.hpp).
//
// Physical constraints hold at every iterate: a trial step at which the run refuses the values
// (an inertia that breaks the triangle inequality or is not positive definite, a mass <= 0) gets
// a residual vector of 1e150 entries, which the solver's step control rejects (its actual
// reduction is negative), shrinking the step until it stays physical.
//
// Identifiability: the condition number of the scaled normal matrix (J D)^T (J D), D the inverse
// column norms of the weighted Jacobian J, above 1e12 at the start or at the solution is refused
// with the combination of keys the data do not determine (the singular vector of the smallest
// singular value), in the keys' names.
#pragma once

#include "fit/residuals.hpp"

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace rotgen {

struct fit_result {
    std::vector<std::string> keys;
    Eigen::VectorXd initial, values, stderrs;
    Eigen::MatrixXd covariance, correlation;
    // Per residual column (fit_residuals::columns): its sigma, the RMS of its residuals, count.
    std::vector<std::string> columns, sigma_names;
    std::vector<double> sigma, rms;
    std::vector<std::size_t> count;
    bool sigma_given = false;  // --sigma; else each column by its own residual RMS
    double variance_scale = 1; // the covariance's factor: chi2/dof without --sigma, else 1
    double chi2 = 0;
    long dof = 0;
    int iterations = 0, evaluations = 0, jacobians = 0;
    std::size_t runs = 0;
    bool sensitivities = false; // the Jacobian from the run's sensitivities (else differences)
    double condition = 0;       // of the scaled normal matrix at the solution
    std::string stop;           // why the solver stopped
    bool converged = false;
    // Per data row: t and the residual of each residual column (model - measured; NaN missing).
    std::vector<double> t;
    Eigen::MatrixXd residuals;
};

// Solves the problem from `x0`; `sigma` per residual column (empty: each column by its own
// residual RMS, two passes). Throws user_error at `where` for a problem not determined by the
// data, or when the run fails at the start.
fit_result solve_fit(const fit_model& model, const fit_residuals& res, Eigen::VectorXd x0,
                     std::vector<double> sigma, const source_location& where, int max_evaluations);

} // namespace rotgen
