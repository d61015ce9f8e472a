#include "run/sensitivity_run.hpp"

#include "run/engine.hpp"
#include "run/prepared.hpp"
#include "support/error.hpp"
#include "support/format.hpp"

#include <cmath>
#include <mutex>

namespace rotgen {

namespace {

using row_major = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

} // namespace

sensitivity_run::sensitivity_run(const prepared_scene& prepared, const member_values& values,
                                 const compiled_form& cf, const std::vector<double>& parameters,
                                 const initial_kinematics& k0)
    : m_scene(prepared.scene()), m_cf(cf), m_parameters(parameters), m_base(cf.system(parameters)),
      m_keys(sensitivity_key_names(m_scene, cf.f)), m_n(cf.f.state.size()) {
    {
        std::lock_guard<std::mutex> lock(symbolic_mutex());
        m_start = start_derivatives_of(m_scene, prepared.derived(), cf.f, values, k0);
    }
    if (!m_scene.sensitivities.error_control) m_scale = std::ldexp(1.0, -300);
    const auto n = static_cast<Eigen::Index>(m_n);
    m_jacobian.resize(n, n);
    m_dfdp.resize(n, static_cast<Eigen::Index>(cf.f.parameters.size()));
}

Eigen::VectorXd sensitivity_run::augmented(const Eigen::VectorXd& y0) const {
    const auto n = static_cast<Eigen::Index>(m_n), k = static_cast<Eigen::Index>(keys());
    Eigen::VectorXd y(n + n * k);
    y.head(n) = y0;
    Eigen::Map<row_major>(y.data() + n, n, k) = m_scale * m_start.dy0;
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
    dS.noalias() += r.m_scale * (dfdp * r.m_start.dP);
}

loaded_system sensitivity_run::system() const {
    loaded_system s;
    s.n = m_n + m_n * keys();
    s.f = &sensitivity_run::rhs;
    s.w = reinterpret_cast<const double*>(this); // rhs casts it back: the kernel's context
    s.p = m_parameters.data();
    return s;
}

double sensitivity_run::tolerance_factor(const scene_spec& scene, std::size_t n) {
    const sensitivity_spec& s = scene.sensitivities;
    if (!s.active() || s.error_control) return 1;
    const std::size_t keys = s.all_initial ? n : s.keys.size();
    return std::sqrt(double(n) / double(n + n * keys));
}

Eigen::MatrixXd sensitivity_run::state_sensitivity(Eigen::Ref<const Eigen::VectorXd> y) const {
    const auto n = static_cast<Eigen::Index>(m_n), k = static_cast<Eigen::Index>(keys());
    return Eigen::Map<const row_major>(y.data() + n, n, k) / m_scale;
}

void sensitivity_run::record(const sample_states& samples, std::size_t rows, bool every,
                             run_result& result) const {
    const std::size_t n = m_n, np = m_cf.f.parameters.size(), k = keys();
    result.sensitivity_keys = m_keys;
    std::vector<std::size_t> columns; // the record program's output of each derived column
    for (std::size_t c = 0; c < m_cf.columns.size(); ++c)
        if (m_cf.columns[c].kind == value_source::compiled) {
            columns.push_back(static_cast<std::size_t>(m_cf.columns[c].index));
            for (const auto& key : m_keys)
                result.sensitivity_columns.push_back("d(" + result.columns[c] + ")/d(" + key + ")");
        }
    std::vector<double> jac(m_cf.outputs * (n + np));
    for (std::size_t s = 0; s < rows; ++s) {
        if (!every && s + 1 != rows) continue;
        const Eigen::Map<const Eigen::VectorXd> y = samples.y(s);
        const Eigen::MatrixXd S = state_sensitivity(y);
        m_cf.record_jacobian(m_parameters.data(), samples.t(s), y.data(), jac.data());
        std::vector<double> out;
        out.reserve(columns.size() * k);
        for (const std::size_t o : columns) {
            const Eigen::Map<const Eigen::RowVectorXd> by_y(&jac[o * (n + np)],
                                                            static_cast<Eigen::Index>(n)),
                by_p(&jac[o * (n + np) + n], static_cast<Eigen::Index>(np));
            const Eigen::RowVectorXd d = by_y * S + by_p * m_start.dP;
            out.insert(out.end(), d.data(), d.data() + d.size());
        }
        result.sensitivity_rows.push_back(std::move(out));
        std::vector<double> flat(n * k);
        Eigen::Map<row_major>(flat.data(), static_cast<Eigen::Index>(n),
                              static_cast<Eigen::Index>(k)) = S;
        result.state_sensitivities.push_back(std::move(flat));
    }
}

void refuse_sensitivity_switch(const scene_spec& scene, double t) {
    throw user_error(scene.sensitivities.where,
                     "sensitivities are not carried across the chart switch this run makes at "
                     "t = " +
                         short_number(t) +
                         "; give switch_chart: false, or form: body, to run them");
}

} // namespace rotgen
