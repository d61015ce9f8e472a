#include "fit/model.hpp"

#include "run/sensitivity_run.hpp"
#include "scene/sensitivities.hpp"
#include "support/error.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>

namespace rotgen {

std::vector<fit_key> resolve_free(const scene_spec& scene, const std::vector<std::string>& free,
                                  const source_location& where) {
    if (free.empty()) throw user_error(where, "no free key (give --free KEY,...)");
    std::vector<fit_key> keys;
    for (const auto& name : free) {
        value_key k;
        k.key = name;
        k.where = where;
        resolve_value_key(scene, k, "free key");
        for (const auto& earlier : keys)
            if (earlier.key == name) throw user_error(where, "key '" + name + "' is free twice");
        fit_key f{name, k.target, k.index, false};
        const auto& g = scene.model.gravity;
        f.positive = k.target == value_key::parameter && g &&
                     g->mass.is_equal(scene.model.parameters[k.index].symbol);
        keys.push_back(f);
    }
    return keys;
}

double key_value(const member_values& values, const fit_key& key) {
    switch (key.target) {
    case value_key::angle:
        return values.angles[key.index];
    case value_key::rate:
        return values.initial_rates[key.index];
    case value_key::parameter:
        break;
    }
    return values.parameters[key.index];
}

void set_key(member_values& values, const fit_key& key, double value) {
    switch (key.target) {
    case value_key::angle:
        values.angles[key.index] = value;
        return;
    case value_key::rate:
        values.initial_rates[key.index] = value;
        return;
    case value_key::parameter:
        values.parameters[key.index] = value;
        return;
    }
}

namespace {

// The scene recording `records` (those it does not record already) at `times` (t_start first),
// with the keys' sensitivities when `sensitivities`.
scene_spec sampled_at(const scene_spec& scene, const std::vector<std::string>& records,
                      const std::vector<double>& times, const std::vector<fit_key>& keys,
                      bool sensitivities) {
    scene_spec s = with_records(scene, records);
    s.sample_at = times;
    if (scene.t_end < scene.t_start) std::reverse(s.sample_at.begin(), s.sample_at.end());
    for (std::size_t k = 0; sensitivities && k < keys.size(); ++k) {
        value_key v;
        v.key = keys[k].key;
        v.where = scene.where;
        v.target = keys[k].target;
        v.index = keys[k].index;
        s.sensitivities.keys.push_back(v);
    }
    s.sensitivities.where = scene.where;
    return s;
}

} // namespace

fit_model::fit_model(const scene_spec& scene, const measured_data& data, std::vector<fit_key> keys,
                     stage_timings& timings)
    : m_keys(std::move(keys)), m_base(values_of(scene)), m_timings(timings) {
    m_times = data.t;
    m_times.push_back(scene.t_start); // the start: the attitude's sign is followed from there
    std::sort(m_times.begin(), m_times.end());
    m_times.erase(std::unique(m_times.begin(), m_times.end()), m_times.end());
    for (double t : data.t)
        m_sample_of.push_back(static_cast<std::size_t>(
            std::lower_bound(m_times.begin(), m_times.end(), t) - m_times.begin()));
    if (scene.t_end < scene.t_start) // a backward run samples from the latest time down
        for (auto& s : m_sample_of)
            s = m_times.size() - 1 - s;
    // the sensitivities wherever the run integrates them, in every form (a run that switches
    // chart refuses them: then differences, evaluate())
    m_sensitivities = method_takes_sensitivities(scene.integrator.method) && !scene.model.rotor;
    {
        const std::lock_guard<std::mutex> lock(symbolic_mutex()); // GiNaC: one thread at a time
        m_prepared = std::make_unique<prepared_scene>(
            sampled_at(scene, measured_records(data), m_times, m_keys, m_sensitivities), timings);
    }
    for (const auto& name : m_prepared->scene().record)
        for (const auto& c : record_columns(name))
            m_columns.push_back(c);
    std::vector<std::string> measured;
    for (const auto& name : measured_records(data))
        for (const auto& c : record_columns(name))
            measured.push_back(c);
    for (const auto& c : m_columns)
        m_needed.push_back(std::find(measured.begin(), measured.end(), c) != measured.end());
}

fit_model::~fit_model() {
    const std::lock_guard<std::mutex> lock(symbolic_mutex());
    m_prepared.reset();
    m_plain.reset();
}

// The run switched chart, which sensitivities do not cross: from now on the scene without them,
// its Jacobian by differences.
void fit_model::without_sensitivities() const {
    scene_spec plain = m_prepared->scene(); // its records and sample times
    plain.sensitivities = {};
    const std::lock_guard<std::mutex> lock(symbolic_mutex());
    m_plain = std::make_unique<prepared_scene>(plain, m_timings);
    m_sensitivities = false;
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

// One run at v; model_failure when it cannot give every sample.
run_result fit_model::run_at(const member_values& v) const {
    for (std::size_t k = 0; k < m_keys.size(); ++k)
        if (m_keys[k].positive && !(key_value(v, m_keys[k]) > 0))
            throw model_failure(m_keys[k].key + " must stay positive");
    ++m_runs;
    run_result r;
    stage_timings scratch; // not the command's: thousands of runs
    try {
        r = run_member(m_plain ? *m_plain : *m_prepared, v, scratch);
    } catch (const sensitivity_switch_refused&) {
        throw;
    } catch (const user_error& e) {
        throw model_failure(e.problem());
    }
    if (!r.ok || r.rows.size() != m_times.size())
        throw model_failure(r.message.empty() ? "the run stopped before the last measurement"
                                              : r.message);
    return r;
}

// The recorded columns of a run (samples x columns).
Eigen::MatrixXd fit_model::columns_of(const run_result& r) const {
    Eigen::MatrixXd y(static_cast<Eigen::Index>(r.rows.size()),
                      static_cast<Eigen::Index>(m_columns.size()));
    for (std::size_t s = 0; s < r.rows.size(); ++s)
        for (std::size_t c = 0; c < m_columns.size(); ++c)
            y(static_cast<Eigen::Index>(s), static_cast<Eigen::Index>(c)) = r.rows[s][c + 1];
    return y;
}

Eigen::MatrixXd fit_model::columns_at(const member_values& v) const {
    return columns_of(run_at(v));
}

model_columns fit_model::evaluate(const Eigen::VectorXd& x, bool derivatives) const {
    const member_values v = values_at(x);
    if (m_sensitivities) {
        try {
            return integrated(v); // one run gives both
        } catch (const sensitivity_switch_refused&) {
            without_sensitivities();
        }
    }
    model_columns m;
    m.y = columns_at(v);
    return derivatives ? differences(v, std::move(m)) : m;
}

// The columns and their derivatives from one run with the keys' sensitivities: d(column)/d(key)
// as the run gives it for every recorded column (the attitude q0..q3 with its sign q0 >= 0, the
// angles with their wrap: the derivatives of the records themselves).
model_columns fit_model::integrated(const member_values& v) const {
    const run_result r = run_at(v);
    model_columns m;
    m.y = columns_of(r);
    const auto samples = static_cast<Eigen::Index>(r.rows.size());
    for (std::size_t k = 0; k < m_keys.size(); ++k) {
        Eigen::MatrixXd d = Eigen::MatrixXd::Zero(samples, m.y.cols());
        for (std::size_t c = 0; c < m_columns.size(); ++c) {
            const std::string name = "d(" + m_columns[c] + ")/d(" + m_keys[k].key + ")";
            const auto& sc = r.sensitivity_columns;
            const auto at = std::find(sc.begin(), sc.end(), name);
            if (at == sc.end() && m_needed[c])
                throw std::logic_error("fit: the run does not give " + name);
            for (Eigen::Index s = 0; at != sc.end() && s < samples; ++s)
                d(s, static_cast<Eigen::Index>(c)) =
                    r.sensitivity_rows[static_cast<std::size_t>(s)]
                                      [static_cast<std::size_t>(at - sc.begin())];
        }
        m.dy.push_back(d);
    }
    return m;
}

// Where the run does not integrate the sensitivities (a method that does not take them, a linear
// rotor, a run that switches chart): the derivatives by central differences of whole runs, step
// 1e-5 max(|value|, 1) per key (one-sided where a side is refused: the edge of the physical
// inertias); angle columns differenced modulo 2 pi.
model_columns fit_model::differences(const member_values& v, model_columns m) const {
    m.dy.clear();
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
