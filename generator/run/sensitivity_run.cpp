#include "run/sensitivity_run.hpp"

#include "run/engine.hpp"
#include "run/prepared.hpp"
#include "scene/sensitivities.hpp"
#include "support/error.hpp"
#include "support/format.hpp"

#include <cmath>
#include <mutex>
#include <stdexcept>

namespace rotgen {

namespace {

using row_major = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

} // namespace

sensitivity_run::sensitivity_run(const prepared_scene& prepared, const member_values& values,
                                 const compiled_form& cf, const std::vector<double>& parameters,
                                 const initial_kinematics& k0)
    : m_scene(prepared.scene()), m_cf(cf), m_parameters(parameters), m_base(cf.system(parameters)),
      m_keys(sensitivity_key_names(m_scene, cf.f)), m_n(cf.f.state.size()) {
    // scene reading refuses the others with a located line; a scene_spec set up in code (the
    // tuner's candidates) must not reach here with one
    if (!method_takes_sensitivities(m_scene.integrator.method))
        throw std::logic_error("run: sensitivities with the method " + m_scene.integrator.method);
    {
        std::lock_guard<std::mutex> lock(symbolic_mutex());
        m_start = start_derivatives_of(m_scene, prepared.derived(), cf.f, values, k0);
    }
    const auto n = static_cast<Eigen::Index>(m_n);
    m_jacobian.resize(n, n);
    m_dfdp.resize(n, static_cast<Eigen::Index>(cf.f.parameters.size()));
    m_forcing.resize(n, static_cast<Eigen::Index>(keys()));
    for (const value_source& c : cf.columns)
        if (c.kind == value_source::compiled)
            m_columns.push_back(static_cast<std::size_t>(c.index));
    if (cf.taylor_sensitivity)
        m_taylor_values = taylor_sensitivity_values(cf.taylor_forcing, m_parameters, m_start.dP);
}

Eigen::VectorXd sensitivity_run::augmented(const Eigen::VectorXd& y0) const {
    const auto n = static_cast<Eigen::Index>(m_n), k = static_cast<Eigen::Index>(keys());
    Eigen::VectorXd y(n + n * k);
    y.head(n) = y0;
    Eigen::Map<row_major>(y.data() + n, n, k) = m_start.dy0;
    return y;
}

// (y, S)' = (f, (d f/d y) S + c (d f/d P) dP/ds), S scaled by c.
void sensitivity_run::rhs(const double* self, double t, const double* y, double* dydt) {
    const auto& r = *reinterpret_cast<const sensitivity_run*>(self);
    const auto n = static_cast<Eigen::Index>(r.m_n), k = static_cast<Eigen::Index>(r.keys());
    r.m_base.rhs(t, y, dydt);
    r.m_base.jacobian(t, y, r.m_jacobian.data()); // row-major into the column-major scratch:
    r.m_cf.parameter_jacobian(r.m_parameters.data(), t, y, r.m_dfdp.data()); // read transposed
    const Eigen::Map<const row_major> J(r.m_jacobian.data(), n, n),
        dfdp(r.m_dfdp.data(), n, r.m_dfdp.cols());
    const Eigen::Map<const row_major> S(y + n, n, k);
    Eigen::Map<row_major> dS(dydt + n, n, k);
    dS.noalias() = J * S;
    r.m_forcing.noalias() = dfdp * r.m_start.dP; // into scratch: no allocation per call
    dS.noalias() += r.m_forcing;
}

loaded_system sensitivity_run::system() const {
    loaded_system s;
    s.n = m_n + m_n * keys();
    s.f = &sensitivity_run::rhs;
    s.w = reinterpret_cast<const double*>(this); // rhs casts it back: the kernel's context
    s.p = m_parameters.data();
    if (m_cf.taylor_sensitivity) {
        s.tay = m_cf.taylor_sensitivity;
        s.series = m_cf.taylor_sensitivity_series;
        s.p = m_taylor_values.data(); // taylor(p, ...) reads them
    }
    return s;
}

error_layout sensitivity_run::layout(const error_layout& state) const {
    error_layout l = state;
    const std::size_t nk = m_n * keys();
    l.groups.resize(m_n + nk, error_layout::itself); // S: each entry relative to itself
    if (!m_scene.sensitivities.error_control) {
        // the state alone: its components weighted so that the RMS over all n + nk components
        // is the state's own RMS (the Taylor method's norm is the largest component: 1); S
        // weighted 0
        const bool largest = m_scene.integrator.method == "taylor";
        l.weights.assign(m_n, largest ? 1.0 : std::sqrt(double(m_n + nk) / double(m_n)));
        l.weights.resize(m_n + nk, 0.0);
    }
    return l;
}

Eigen::MatrixXd sensitivity_run::state_sensitivity(Eigen::Ref<const Eigen::VectorXd> y) const {
    const auto n = static_cast<Eigen::Index>(m_n), k = static_cast<Eigen::Index>(keys());
    return Eigen::Map<const row_major>(y.data() + n, n, k);
}

std::vector<double> sensitivity_run::column_derivatives(double t,
                                                        Eigen::Ref<const Eigen::VectorXd> y,
                                                        const Eigen::MatrixXd& S) const {
    const std::size_t n = m_n, np = m_cf.f.parameters.size();
    std::vector<double> jac(m_cf.outputs * (n + np)), out;
    m_cf.record_jacobian(m_parameters.data(), t, y.data(), jac.data());
    out.reserve(m_columns.size() * keys());
    for (const std::size_t o : m_columns) {
        const Eigen::Map<const Eigen::RowVectorXd> by_y(&jac[o * (n + np)],
                                                        static_cast<Eigen::Index>(n)),
            by_p(&jac[o * (n + np) + n], static_cast<Eigen::Index>(np));
        const Eigen::RowVectorXd d = by_y * S + by_p * m_start.dP; // the chain rule
        out.insert(out.end(), d.data(), d.data() + d.size());
    }
    return out;
}

Eigen::RowVectorXd sensitivity_run::event_time(std::size_t which, double t,
                                               Eigen::Ref<const Eigen::VectorXd> y,
                                               Eigen::MatrixXd& S) const {
    const auto n = static_cast<Eigen::Index>(m_n), np = m_start.dP.rows();
    Eigen::RowVectorXd g(n + np + 1); // g by (y, P, t)
    m_cf.event_jacobians[which](m_parameters.data(), t, y.data(), g.data());
    Eigen::VectorXd f(n);
    m_base.rhs(t, y.data(), f.data());
    const double rate = g[n + np] + g.head(n).dot(f); // dg/dt along the motion
    const Eigen::RowVectorXd dt =
        -(g.head(n) * S + g.segment(n, np) * m_start.dP) / rate; // (4.8) of the issue
    S += f * dt;
    return dt;
}

void sensitivity_run::record(const sample_states& samples, std::size_t rows, bool every,
                             run_result& result) const {
    const std::size_t n = m_n, k = keys();
    result.sensitivity_keys = m_keys;
    for (std::size_t c = 0; c < m_cf.columns.size(); ++c)
        if (m_cf.columns[c].kind == value_source::compiled)
            for (const auto& key : m_keys)
                result.sensitivity_columns.push_back("d(" + result.columns[c] + ")/d(" + key + ")");
    for (std::size_t s = 0; s < rows; ++s) {
        if (!every && s + 1 != rows) continue;
        const Eigen::Map<const Eigen::VectorXd> y = samples.y(s);
        Eigen::MatrixXd S = state_sensitivity(y);
        if (result.stopped_by >= 0 && s + 1 == samples.size()) // the terminal event's state
            event_time(static_cast<std::size_t>(result.stopped_by), samples.t(s), y, S);
        result.sensitivity_rows.push_back(column_derivatives(samples.t(s), y, S));
        std::vector<double> flat(n * k);
        Eigen::Map<row_major>(flat.data(), static_cast<Eigen::Index>(n),
                              static_cast<Eigen::Index>(k)) = S;
        result.state_sensitivities.push_back(std::move(flat));
    }
}

void sensitivity_run::record_event(std::size_t which, double t, Eigen::Ref<const Eigen::VectorXd> y,
                                   run_result& result) const {
    if (result.event_sensitivity_columns.empty()) {
        for (const auto& key : m_keys)
            result.event_sensitivity_columns.push_back("d(t_event)/d(" + key + ")");
        for (std::size_t c = 0; c < m_cf.columns.size(); ++c)
            if (m_cf.columns[c].kind == value_source::compiled)
                for (const auto& key : m_keys)
                    result.event_sensitivity_columns.push_back("d(" + result.columns[c] + ")/d(" +
                                                               key + ")");
    }
    Eigen::MatrixXd S = state_sensitivity(y);
    const Eigen::RowVectorXd dt = event_time(which, t, y, S);
    std::vector<double> row(dt.data(), dt.data() + dt.size());
    const std::vector<double> columns = column_derivatives(t, y, S);
    row.insert(row.end(), columns.begin(), columns.end());
    result.event_sensitivity_rows.push_back(std::move(row));
}

void refuse_sensitivity_switch(const scene_spec& scene, double t) {
    throw user_error(scene.sensitivities.where,
                     "sensitivities are not carried across the chart switch this run makes at "
                     "t = " +
                         short_number(t) +
                         "; give switch_chart: false, or form: body, to run them");
}

} // namespace rotgen
