#include "fit/solve.hpp"

#include "support/error.hpp"
#include "support/format.hpp"

#include <unsupported/Eigen/NonLinearOptimization>

#include <cmath>
#include <limits>

namespace rotgen {

namespace {

constexpr double penalty = 1e150;        // a residual at values the run refuses
constexpr double ill_conditioned = 1e12; // of the scaled normal matrix

// The weighted residuals w r (w = 1/sigma of each residual's column) for Eigen's solver.
class weighted_problem {
  public:
    using Scalar = double;
    using InputType = Eigen::VectorXd;
    using ValueType = Eigen::VectorXd;
    using JacobianType = Eigen::MatrixXd;
    enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };

    weighted_problem(const fit_model& model, const fit_residuals& res, Eigen::VectorXd w)
        : m_model(model), m_res(res), m_w(std::move(w)) {}
    int inputs() const { return static_cast<int>(m_model.keys().size()); }
    int values() const { return static_cast<int>(m_res.size()); }

    int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& f) const {
        try {
            m_last = m_model.evaluate(x, false); // with sensitivities: the derivatives too
            m_last_x = x;
            m_res.compute(m_last, f, nullptr);
            f = f.cwiseProduct(m_w);
        } catch (const model_failure&) {
            f = Eigen::VectorXd::Constant(values(), penalty);
        }
        return 0;
    }
    int df(const Eigen::VectorXd& x, Eigen::MatrixXd& J) const {
        Eigen::VectorXd r;
        if (m_last.dy.empty() || m_last_x.size() != x.size() || m_last_x != x)
            m_last = m_model.evaluate(x, true), m_last_x = x; // x: an accepted, physical point
        m_res.compute(m_last, r, &J);
        J = m_w.asDiagonal() * J;
        return 0;
    }
    const Eigen::VectorXd& weights() const { return m_w; }

  private:
    const fit_model& m_model;
    const fit_residuals& m_res;
    Eigen::VectorXd m_w;
    mutable model_columns m_last; // the last evaluation (the solver asks for J where it was)
    mutable Eigen::VectorXd m_last_x;
};

std::string stop_words(Eigen::LevenbergMarquardtSpace::Status s, bool& converged) {
    using namespace Eigen::LevenbergMarquardtSpace;
    converged = s != TooManyFunctionEvaluation && s != ImproperInputParameters && s != UserAsked;
    switch (s) {
    case RelativeReductionTooSmall:
        return "the relative reduction of chi2 fell below 1e-8";
    case RelativeErrorTooSmall:
        return "the relative step in the keys fell below 1e-8";
    case RelativeErrorAndReductionTooSmall:
        return "the relative reduction of chi2 and the relative step both fell below 1e-8";
    case CosinusTooSmall:
        return "the residuals are orthogonal to the Jacobian's columns";
    case TooManyFunctionEvaluation:
        return "the evaluations ran out before convergence";
    case FtolTooSmall:
    case XtolTooSmall:
    case GtolTooSmall:
        return "no further reduction is possible in double precision";
    default:
        return "the solver could not start";
    }
}

// Per residual column: RMS of the unweighted residuals r and their count.
void column_rms(const fit_residuals& res, const Eigen::VectorXd& r, std::vector<double>& rms,
                std::vector<std::size_t>& count) {
    rms.assign(res.columns().size(), 0);
    count.assign(res.columns().size(), 0);
    for (std::size_t i = 0; i < res.size(); ++i)
        rms[res.column(i)] += r[static_cast<Eigen::Index>(i)] * r[static_cast<Eigen::Index>(i)],
            ++count[res.column(i)];
    for (std::size_t c = 0; c < rms.size(); ++c)
        rms[c] = count[c] ? std::sqrt(rms[c] / double(count[c])) : 0;
}

Eigen::VectorXd weights_of(const fit_residuals& res, const std::vector<double>& sigma) {
    Eigen::VectorXd w(static_cast<Eigen::Index>(res.size()));
    for (std::size_t i = 0; i < res.size(); ++i)
        w[static_cast<Eigen::Index>(i)] = 1 / sigma[res.column(i)];
    return w;
}

// The condition number of (J D)^T (J D), D the inverse column norms; `null` the direction (in
// the keys, unscaled) of the smallest singular value.
double scaled_condition(const Eigen::MatrixXd& J, Eigen::VectorXd& null) {
    Eigen::VectorXd d = J.colwise().norm().transpose();
    for (Eigen::Index k = 0; k < d.size(); ++k)
        d[k] = d[k] > 0 ? 1 / d[k] : 1;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J * d.asDiagonal(), Eigen::ComputeThinV);
    const Eigen::VectorXd s = svd.singularValues();
    null = d.asDiagonal() * svd.matrixV().col(s.size() - 1);
    const double smin = s[s.size() - 1];
    return smin > 0 ? (s[0] / smin) * (s[0] / smin) : std::numeric_limits<double>::infinity();
}

// The message for a direction the data do not determine.
[[noreturn]] void not_identifiable(const fit_model& model, const Eigen::VectorXd& x,
                                   const Eigen::VectorXd& null, double condition,
                                   const std::string& when, const source_location& where) {
    const Eigen::VectorXd v = null / null.cwiseAbs().maxCoeff();
    std::string keys, ratio, largest;
    double big = 0;
    for (Eigen::Index k = 0; k < v.size(); ++k) {
        if (std::abs(v[k]) < 0.05) continue;
        const std::string& key = model.keys()[static_cast<std::size_t>(k)].key;
        keys += (keys.empty() ? "" : ", ") + key;
        ratio += (ratio.empty() ? "" : " : ") + short_number(v[k]);
        if (std::abs(v[k]) > big) big = std::abs(v[k]), largest = key;
    }
    const double cosine = std::abs(x.dot(null)) / (x.norm() * null.norm());
    const std::string scale = cosine > 0.999 ? " (a common scale of these keys: the motion is "
                                               "unchanged when they are all multiplied by c)"
                                             : "";
    throw user_error(where, "the data do not determine " + keys + " together (condition number " +
                                short_number(condition) + " of the scaled J^T W J " + when +
                                " > 1e12): changing them in the ratio " + ratio +
                                " leaves the fit unchanged" + scale + "; fix one of them, e.g. " +
                                largest + " (leave it out of --free)");
}

// The statistics at the solution x: chi2, covariance (scaled by chi2/dof without --sigma),
// standard errors, correlation, residuals per column; refuses an undetermined solution.
void at_solution(const fit_model& model, const fit_residuals& res, const Eigen::VectorXd& x,
                 const source_location& where, fit_result& out) {
    Eigen::VectorXd r, null;
    Eigen::MatrixXd J;
    res.compute(model.evaluate(x, true), r, &J);
    const Eigen::VectorXd w = weights_of(res, out.sigma);
    const Eigen::MatrixXd Jw = w.asDiagonal() * J;
    out.values = x;
    out.chi2 = r.cwiseProduct(w).squaredNorm();
    out.dof = static_cast<long>(res.size()) - static_cast<long>(x.size());
    out.condition = scaled_condition(Jw, null);
    if (out.converged && out.condition > ill_conditioned)
        not_identifiable(model, x, null, out.condition, "at the solution", where);
    out.variance_scale = out.sigma_given ? 1.0 : out.chi2 / double(out.dof);
    const Eigen::MatrixXd normal = Jw.transpose() * Jw;
    out.covariance = out.variance_scale * normal.completeOrthogonalDecomposition().pseudoInverse();
    out.stderrs = out.covariance.diagonal().cwiseSqrt();
    out.correlation = out.stderrs.cwiseInverse().asDiagonal() * out.covariance *
                      out.stderrs.cwiseInverse().asDiagonal();
    column_rms(res, r, out.rms, out.count);
    out.residuals = Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(out.t.size()),
                                              static_cast<Eigen::Index>(res.columns().size()),
                                              std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < res.size(); ++i)
        out.residuals(static_cast<Eigen::Index>(res.row(i)),
                      static_cast<Eigen::Index>(res.column(i))) = r[static_cast<Eigen::Index>(i)];
}

// The weighted residuals and Jacobian at the start; the sigmas from their RMS when not given.
void at_start(const fit_model& model, const fit_residuals& res, const Eigen::VectorXd& x0,
              const source_location& where, fit_result& out) {
    model_columns m;
    try {
        m = model.evaluate(x0, true);
    } catch (const model_failure& e) {
        throw user_error(where, std::string("the model cannot run at the start: ") + e.what());
    }
    Eigen::VectorXd r, null;
    Eigen::MatrixXd J;
    res.compute(m, r, &J);
    if (!out.sigma_given) {
        column_rms(res, r, out.sigma, out.count);
        for (double& s : out.sigma)
            s = s > 0 ? s : 1;
    }
    const double condition = scaled_condition(weights_of(res, out.sigma).asDiagonal() * J, null);
    if (condition > ill_conditioned)
        not_identifiable(model, x0, null, condition, "at the start", where);
}

} // namespace

fit_result solve_fit(const fit_model& model, const fit_residuals& res, Eigen::VectorXd x0,
                     std::vector<double> sigma, const source_location& where, int max_evaluations) {
    fit_result out;
    for (const auto& k : model.keys())
        out.keys.push_back(k.key);
    out.columns = res.columns();
    out.sigma_names = res.sigma_names();
    out.initial = x0;
    out.sigma_given = !sigma.empty();
    out.sigma = std::move(sigma);
    out.t = res.data().t;
    if (res.size() <= static_cast<std::size_t>(x0.size()))
        throw user_error(where, std::to_string(res.size()) + " measured values for " +
                                    std::to_string(x0.size()) +
                                    " free keys: a fit needs more measurements than keys");
    at_start(model, res, x0, where, out);
    Eigen::VectorXd x = x0;
    for (int pass = 0; pass < (out.sigma_given ? 1 : 2); ++pass) {
        if (pass == 1) { // each column weighted by its own residual RMS at the first solution
            Eigen::VectorXd r;
            res.compute(model.evaluate(x, false), r, nullptr);
            column_rms(res, r, out.sigma, out.count);
            for (double& s : out.sigma)
                s = s > 0 ? s : 1;
        }
        weighted_problem problem(model, res, weights_of(res, out.sigma));
        Eigen::LevenbergMarquardt<weighted_problem> lm(problem);
        lm.parameters.ftol = lm.parameters.xtol = 1e-8; // the runs are not exact: not below
        lm.parameters.maxfev = max_evaluations;
        const auto status = lm.minimize(x);
        out.stop = stop_words(status, out.converged);
        out.iterations += static_cast<int>(lm.iter);
        out.evaluations += static_cast<int>(lm.nfev);
        out.jacobians += static_cast<int>(lm.njev);
        if (!out.converged) break;
    }
    at_solution(model, res, x, where, out);
    out.runs = model.runs();
    out.sensitivities = model.sensitivities();
    return out;
}

} // namespace rotgen
