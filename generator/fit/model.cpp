#include "fit/model.hpp"

#include "support/error.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>

namespace rotgen {

std::vector<fit_key> resolve_free(const scene_spec& scene, const std::vector<std::string>& free,
                                  const source_location& where) {
    if (free.empty()) throw user_error(where, "no free key (give --free KEY,...)");
    std::vector<fit_key> keys;
    for (const auto& name : free) {
        sweep_key k;
        k.key = name;
        k.where = where;
        resolve_sweep_key(scene, k);
        for (const auto& earlier : keys)
            if (earlier.key == name) throw user_error(where, "key '" + name + "' is free twice");
        fit_key f{name, k.target, k.index, false};
        const auto& g = scene.model.gravity;
        f.positive = k.target == sweep_key::parameter && g &&
                     g->mass.is_equal(scene.model.parameters[k.index].symbol);
        keys.push_back(f);
    }
    return keys;
}

double key_value(const member_values& values, const fit_key& key) {
    switch (key.target) {
    case sweep_key::angle:
        return values.angles[key.index];
    case sweep_key::rate:
        return values.initial_rates[key.index];
    case sweep_key::parameter:
        break;
    }
    return values.parameters[key.index];
}

void set_key(member_values& values, const fit_key& key, double value) {
    switch (key.target) {
    case sweep_key::angle:
        values.angles[key.index] = value;
        return;
    case sweep_key::rate:
        values.initial_rates[key.index] = value;
        return;
    case sweep_key::parameter:
        values.parameters[key.index] = value;
        return;
    }
}

namespace {

// The scene recording `records` (those it does not record already) at `times`.
scene_spec sampled_at(const scene_spec& scene, const std::vector<std::string>& records,
                      const std::vector<double>& times) {
    scene_spec s = with_records(scene, records);
    s.sample_at = times;
    if (scene.t_end < scene.t_start) std::reverse(s.sample_at.begin(), s.sample_at.end());
    return s;
}

} // namespace

fit_model::fit_model(const scene_spec& scene, const measured_data& data, std::vector<fit_key> keys,
                     stage_timings& timings)
    : m_keys(std::move(keys)), m_base(values_of(scene)), m_timings(timings) {
    m_times = data.t;
    std::sort(m_times.begin(), m_times.end());
    m_times.erase(std::unique(m_times.begin(), m_times.end()), m_times.end());
    for (double t : data.t)
        m_sample_of.push_back(static_cast<std::size_t>(
            std::lower_bound(m_times.begin(), m_times.end(), t) - m_times.begin()));
    if (scene.t_end < scene.t_start) // a backward run samples from the latest time down
        for (auto& s : m_sample_of)
            s = m_times.size() - 1 - s;
    const std::lock_guard<std::mutex> lock(symbolic_mutex()); // GiNaC: one thread at a time
    m_prepared = std::make_unique<prepared_scene>(
        sampled_at(scene, measured_records(data), m_times), timings);
    for (const auto& name : m_prepared->scene().record)
        for (const auto& c : record_columns(name))
            m_columns.push_back(c);
}

fit_model::~fit_model() {
    const std::lock_guard<std::mutex> lock(symbolic_mutex());
    m_prepared.reset();
}

std::size_t fit_model::column(const std::string& name) const {
    return static_cast<std::size_t>(std::find(m_columns.begin(), m_columns.end(), name) -
                                    m_columns.begin());
}

Eigen::VectorXd fit_model::start() const {
    Eigen::VectorXd x(static_cast<Eigen::Index>(m_keys.size()));
    for (std::size_t k = 0; k < m_keys.size(); ++k)
        x[static_cast<Eigen::Index>(k)] = key_value(m_base, m_keys[k]);
    return x;
}

member_values fit_model::values_at(const Eigen::VectorXd& x) const {
    member_values v = m_base;
    for (std::size_t k = 0; k < m_keys.size(); ++k)
        set_key(v, m_keys[k], x[static_cast<Eigen::Index>(k)]);
    return v;
}

// One run: the recorded columns at the times (samples x columns).
Eigen::MatrixXd fit_model::columns_at(const member_values& v) const {
    for (std::size_t k = 0; k < m_keys.size(); ++k)
        if (m_keys[k].positive && !(key_value(v, m_keys[k]) > 0))
            throw model_failure(m_keys[k].key + " must stay positive");
    ++m_runs;
    run_result r;
    try {
        r = run_member(*m_prepared, v, m_timings);
    } catch (const user_error& e) {
        throw model_failure(e.problem());
    }
    if (!r.ok || r.rows.size() != m_times.size())
        throw model_failure(r.message.empty() ? "the run stopped before the last measurement"
                                              : r.message);
    Eigen::MatrixXd y(static_cast<Eigen::Index>(r.rows.size()),
                      static_cast<Eigen::Index>(m_columns.size()));
    for (std::size_t s = 0; s < r.rows.size(); ++s)
        for (std::size_t c = 0; c < m_columns.size(); ++c)
            y(static_cast<Eigen::Index>(s), static_cast<Eigen::Index>(c)) = r.rows[s][c + 1];
    return y;
}

// TEMPORARY (until the sensitivities of issue 48 land): the derivatives by central differences
// of whole runs, step 1e-5 max(|value|, 1) per key (one-sided where a side is refused: the edge
// of the physical inertias); angle columns differenced modulo 2 pi.
model_columns fit_model::evaluate(const Eigen::VectorXd& x, bool derivatives) const {
    model_columns m;
    const member_values v = values_at(x);
    m.y = columns_at(v);
    if (!derivatives) return m;
    const auto& q = scene().model.angles.names;
    for (std::size_t k = 0; k < m_keys.size(); ++k) {
        const double h = 1e-5 * std::max(std::abs(key_value(v, m_keys[k])), 1.0);
        const auto side = [&](double step, Eigen::MatrixXd& out) {
            member_values moved = v;
            set_key(moved, m_keys[k], key_value(v, m_keys[k]) + step);
            try {
                out = columns_at(moved);
                return true;
            } catch (const model_failure&) {
                return false;
            }
        };
        Eigen::MatrixXd plus, minus;
        const bool up = side(h, plus), down = side(-h, minus);
        if (!up && !down) throw model_failure("no difference step is physical");
        Eigen::MatrixXd d = (up ? plus : m.y) - (down ? minus : m.y);
        for (std::size_t c = 0; c < m_columns.size(); ++c)
            if (std::find(q.begin(), q.end(), m_columns[c]) != q.end())
                for (Eigen::Index s = 0; s < d.rows(); ++s)
                    d(s, static_cast<Eigen::Index>(c)) = std::remainder(
                        d(s, static_cast<Eigen::Index>(c)), 2 * 3.14159265358979323846);
        m.dy.push_back(d / ((up && down ? 2 : 1) * h));
    }
    return m;
}

} // namespace rotgen
