#include "run/sensitivity_run.hpp"

#include "run/engine.hpp"
#include "run/prepared.hpp"
#include "run/source_value.hpp"
#include "scene/sensitivities.hpp"
#include "support/error.hpp"
#include "support/format.hpp"

#include <cmath>
#include <mutex>
#include <stdexcept>

namespace rotgen {

namespace {

using row_major = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// d(<column>)/d(<key>) for every recorded column, record order then key order.
std::vector<std::string> derivative_names(const std::vector<std::string>& columns,
                                          const std::vector<std::string>& keys) {
    std::vector<std::string> names;
    for (const auto& column : columns)
        for (const auto& key : keys)
            names.push_back("d(" + column + ")/d(" + key + ")");
    return names;
}

} // namespace

sensitivity_run::sensitivity_run(const prepared_scene& prepared, const member_values& values,
                                 const compiled_form& cf, const std::vector<double>& parameters,
                                 const initial_kinematics& k0)
    : m_scene(prepared.scene()), m_cf(cf), m_parameters(parameters), m_base(cf.system(parameters)),
      m_keys(sensitivity_key_names(m_scene, cf.f)), m_n(cf.f.state.size()),
      m_sequence(sequence_of(m_scene.model.angles)) {
    // scene reading refuses the others with a located line; a scene_spec set up in code (the
    // tuner's candidates) must not reach here with one
    if (!method_takes_sensitivities(m_scene.integrator.method))
        throw std::logic_error("run: sensitivities with the method " + m_scene.integrator.method);
    {
        std::lock_guard<std::mutex> lock(symbolic_mutex());
        m_start = start_derivatives_of(m_scene, prepared.derived(), cf.f, values, k0);
    }
    // the variational kernel's v: the parameter values, then dP/ds row-major
    m_context = m_parameters;
    for (Eigen::Index p = 0; p < m_start.dP.rows(); ++p)
        for (Eigen::Index j = 0; j < m_start.dP.cols(); ++j)
            m_context.push_back(m_start.dP(p, j));
    for (const value_source& c : cf.columns)
        m_sampled = m_sampled || c.kind != value_source::compiled;
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

loaded_system sensitivity_run::system() const {
    loaded_system s;
    s.n = m_n + m_n * keys();
    s.f = m_cf.variational; // (y, S)' compiled as one kernel (run/variational.hpp)
    s.w = m_context.data();
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

// Every recorded column's d(column)/d(key): the record program's outputs by the chain rule through
// their generated derivatives, d out = (d out/d y) S + (d out/d P) dP/ds; the columns computed at
// the sample (angles from the quaternion, q from the angles, ...) by the same code on duals whose
// derivatives are S's rows and those of the outputs (run/source_value.hpp).
std::vector<double> sensitivity_run::column_derivatives(double t,
                                                        Eigen::Ref<const Eigen::VectorXd> y,
                                                        const Eigen::MatrixXd& S) const {
    const auto n = static_cast<Eigen::Index>(m_n), k = static_cast<Eigen::Index>(keys());
    const auto np = static_cast<Eigen::Index>(m_cf.f.parameters.size()),
               outputs = static_cast<Eigen::Index>(m_cf.outputs);
    std::vector<double> jac(m_cf.outputs * static_cast<std::size_t>(n + np));
    m_cf.record_jacobian(m_parameters.data(), t, y.data(), jac.data());
    const Eigen::Map<const row_major> by(jac.data(), outputs, n + np);
    const Eigen::MatrixXd dout =
        by.leftCols(n) * S + by.rightCols(np) * m_start.dP; // the chain rule
    std::vector<dual> yd, od; // with the sampled columns: the state and the outputs as duals
    if (m_sampled) {
        std::vector<double> values(m_cf.outputs);
        m_cf.record(m_parameters.data(), t, y.data(), values.data());
        for (Eigen::Index i = 0; i < n; ++i)
            yd.emplace_back(y[i], S.row(i).transpose());
        for (Eigen::Index o = 0; o < outputs; ++o)
            od.emplace_back(values[static_cast<std::size_t>(o)], dout.row(o).transpose());
    }
    const mat3<dual> unused = mat3<dual>::Zero(); // l = I omega comes from the record program
    std::optional<std::array<dual, 3>> e;
    std::vector<double> out;
    out.reserve(m_cf.columns.size() * keys());
    for (const value_source& c : m_cf.columns) {
        Eigen::VectorXd d = Eigen::VectorXd::Zero(k);
        if (c.kind == value_source::compiled)
            d = dout.row(c.index).transpose();
        else if (const dual v =
                     source_value_of<dual>(m_sequence, c, yd.data(), od.data(), unused, e);
                 v.d.size() == k)
            d = v.d;
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
    result.sensitivity_columns = derivative_names(result.columns, m_keys);
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
        for (const auto& name : derivative_names(result.columns, m_keys))
            result.event_sensitivity_columns.push_back(name);
    }
    Eigen::MatrixXd S = state_sensitivity(y);
    const Eigen::RowVectorXd dt = event_time(which, t, y, S);
    std::vector<double> row(dt.data(), dt.data() + dt.size());
    const std::vector<double> columns = column_derivatives(t, y, S);
    row.insert(row.end(), columns.begin(), columns.end());
    result.event_sensitivity_rows.push_back(std::move(row));
}

void refuse_sensitivity_switch(const scene_spec& scene, double t) {
    throw sensitivity_switch_refused(
        scene.sensitivities.where,
        "sensitivities are not carried across the chart switch this run makes at "
        "t = " +
            short_number(t) + "; give switch_chart: false, or form: body, to run them");
}

} // namespace rotgen
