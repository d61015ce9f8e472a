#include "fit/residuals.hpp"

#include <cmath>

namespace rotgen {

namespace {

constexpr double two_pi = 2 * 3.14159265358979323846;

// a^-1 (x) b for unit quaternions (scalar first): conj(a) b.
Eigen::Vector4d relative(const Eigen::Vector4d& a, const Eigen::Vector4d& b) {
    const Eigen::Quaterniond qa(a[0], a[1], a[2], a[3]), qb(b[0], b[1], b[2], b[3]);
    const Eigen::Quaterniond d = qa.conjugate() * qb;
    return {d.w(), d.x(), d.y(), d.z()};
}

} // namespace

Eigen::Vector3d rotation_vector(const Eigen::Vector4d& q_in) {
    Eigen::Vector4d q = q_in / q_in.norm();
    if (q[0] < 0) q = -q;
    const Eigen::Vector3d v = q.tail<3>();
    const double s = v.norm();
    if (s < 1e-8) return 2 * v / q[0]; // 2 atan2(s, w) / s = 2 / w (1 + O(s^2))
    return 2 * std::atan2(s, q[0]) / s * v;
}

fit_residuals::fit_residuals(const measured_data& data, const fit_model& model)
    : m_data(data), m_model(model) {
    const auto& q = model.scene().model.angles.names;
    for (std::size_t c = 0; c < data.columns.size(); ++c) {
        const std::string& name = data.columns[c];
        source s{c, model.column(name == "q" ? "q0" : name)};
        s.attitude = name == "q";
        s.angle = name == q[0] || name == q[1] || name == q[2];
        m_sources.push_back(s);
    }
    std::vector<std::size_t> first(data.columns.size()); // each data column's first residual column
    for (std::size_t c = 0; c < data.columns.size(); ++c) {
        first[c] = m_columns.size();
        if (m_sources[c].attitude) {
            for (const char* n : {"attitude1", "attitude2", "attitude3"})
                m_columns.push_back(n), m_sigma_names.push_back("q");
        } else {
            m_columns.push_back(data.columns[c]), m_sigma_names.push_back(data.columns[c]);
        }
    }
    for (std::size_t r = 0; r < data.t.size(); ++r)
        for (std::size_t c = 0; c < data.columns.size(); ++c) {
            const bool present =
                m_sources[c].attitude ? !std::isnan(data.q[r][0]) : !std::isnan(data.values[c][r]);
            for (std::size_t k = 0; present && k < (m_sources[c].attitude ? 3u : 1u); ++k) {
                m_row.push_back(r);
                m_column.push_back(first[c] + k);
                m_source.push_back(c);
            }
        }
}

void fit_residuals::compute(const model_columns& m, Eigen::VectorXd& r, Eigen::MatrixXd* J) const {
    const auto n = static_cast<Eigen::Index>(size());
    const auto keys = static_cast<Eigen::Index>(m.dy.size());
    r.resize(n);
    if (J) J->resize(n, keys);
    for (Eigen::Index i = 0; i < n; ++i) {
        const std::size_t row = m_row[static_cast<std::size_t>(i)];
        const source& src = m_sources[m_source[static_cast<std::size_t>(i)]];
        const auto s = static_cast<Eigen::Index>(m_model.sample_of(row));
        const auto c = static_cast<Eigen::Index>(src.model_column);
        if (src.attitude) {
            attitude(m, row, static_cast<std::size_t>(s), src.model_column,
                     static_cast<std::size_t>(i), r, J);
            i += 2;
            continue;
        }
        const double d = m.y(s, c) - m_data.values[src.data_column][row];
        r[i] = src.angle ? std::remainder(d, two_pi) : d;
        for (Eigen::Index k = 0; J && k < keys; ++k)
            (*J)(i, k) = m.dy[static_cast<std::size_t>(k)](s, c);
    }
}

// The three attitude residuals of `row` at residual index i.., and their derivatives: the
// rotation vector's derivative along each key's dq (the sensitivity of the model's quaternion),
// by a central difference of that closed-form map (step 1e-6 of the unit quaternion).
void fit_residuals::attitude(const model_columns& m, std::size_t row, std::size_t s, std::size_t q0,
                             std::size_t i, Eigen::VectorXd& r, Eigen::MatrixXd* J) const {
    const auto si = static_cast<Eigen::Index>(s), c = static_cast<Eigen::Index>(q0);
    const auto ii = static_cast<Eigen::Index>(i);
    const Eigen::Vector4d measured(m_data.q[row][0], m_data.q[row][1], m_data.q[row][2],
                                   m_data.q[row][3]);
    const Eigen::Vector4d model = m.y.block(si, c, 1, 4).transpose();
    r.segment<3>(ii) = rotation_vector(relative(measured, model / model.norm()));
    for (std::size_t k = 0; J && k < m.dy.size(); ++k) {
        const Eigen::Vector4d dq = m.dy[k].block(si, c, 1, 4).transpose();
        const double h = 1e-6 / std::max(dq.norm(), 1e-300);
        const Eigen::Vector4d plus = model + h * dq, minus = model - h * dq;
        const Eigen::Vector3d a = rotation_vector(relative(measured, plus / plus.norm()));
        const Eigen::Vector3d b = rotation_vector(relative(measured, minus / minus.norm()));
        J->block(ii, static_cast<Eigen::Index>(k), 3, 1) =
            dq.norm() == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d((a - b) / (2 * h));
    }
}

} // namespace rotgen
