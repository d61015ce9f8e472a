#include "run/engine.hpp"

#include "expr/numbers.hpp"
#include "expr/symbols.hpp"
#include "run/actions.hpp"
#include "run/angle_chart.hpp"
#include "run/chart_kinematics.hpp"
#include "run/continue_from.hpp"
#include "run/kinematics.hpp"
#include "run/prepared.hpp"
#include "run/rotor_chart.hpp"
#include "run/run_rules.hpp"
#include "run/sensitivity_run.hpp"
#include "run/split_run.hpp"
#include "run/start_check.hpp"
#include "run/tolerance_layout.hpp"
#include "support/error.hpp"
#include "support/format.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>
#include <utility>

namespace rotgen {

namespace {

// Below this |sin theta| at a sample, an Euler-angle run continues in the body form; above
// switch_back_above it returns to the Euler-angle form (hysteresis: no switching to and fro).
constexpr double switch_below = 0.1, switch_back_above = 0.3;

struct sample {
    double t;
    Eigen::VectorXd y;
    std::size_t form; // index into scene_run::m_compiled
};

// One member's run on a prepared scene: its own initial values and parameter values, the
// prepared (shared, immutable) kernels. Touches GiNaC only under symbolic_mutex().
class scene_run {
  public:
    scene_run(const prepared_scene& prepared, const member_values& values, stage_timings& timings,
              const sample_callback& on_sample)
        : m_prepared(prepared), m_scene(prepared.scene()), m_angles(m_scene.model.angles),
          m_sequence(sequence_of(m_angles)), m_values(values), m_timings(timings),
          m_on_sample(on_sample) {}
    run_result run();
    // The run in parts (member_parts): the start, the chart test of a sample, the records.
    Eigen::VectorXd start();
    bool keeps_chart(std::size_t sample, double t, const Eigen::VectorXd& y) const;
    run_result finish_from(const sample_states& samples, const step_stats& stats,
                           std::vector<member_event> events, int stopped_by);
    bool starts_in_body() const { return m_start_in_body; }
    const std::vector<double>& parameters() const { return m_parameters[m_current]; }

  private:
    run_result finish(); // the run's result, moved out: called once, at the end
    initial_kinematics exact_start();
    void decide_chart();
    const compiled_form& compile(form_kind form);
    Eigen::VectorXd state_of(const form_expressions& f, const initial_kinematics& k) const {
        return form_state(f, k, m_angles, m_scene.form);
    }
    enum class next {
        done,
        body,
        euler,
        act
    }; // after a segment: finished, continue in that
       // chart, or act (m_pending) and continue
    next integrate_segment(Eigen::VectorXd& y, double t_from);
    void set_up_events();
    void use_event_functions(const compiled_form& cf);
    void collect_events(std::size_t from);
    void end_at_event(std::size_t which);
    bool act(Eigen::VectorXd& y, double& t_from);
    void note_event(double t, const Eigen::VectorXd& y, std::size_t index, const char* phase);
    void switch_chart(next to, Eigen::VectorXd& y, double& t_from);
    void record();
    const compiled_form& record_outputs(double t, Eigen::Ref<const Eigen::VectorXd> y,
                                        std::size_t form, std::vector<double>& out) const;
    std::vector<double> record_row(double t, Eigen::Ref<const Eigen::VectorXd> y, std::size_t form,
                                   std::vector<double>& out) const;
    void start_method();

    const prepared_scene& m_prepared;
    const scene_spec& m_scene; // the prepared scene (shared): read, never copied outside the lock
    const angle_convention& m_angles; // the model's (m_scene.model.angles): names, sequence
    const euler_sequence m_sequence;  // its sequence, for the runtime's conversions
    const member_values& m_values;
    stage_timings& m_timings;
    const sample_callback& m_on_sample;
    Eigen::Matrix3d m_inertia;
    std::vector<long double> m_model_parameters;   // this member's, exact to long double
    std::vector<const compiled_form*> m_compiled;  // the forms this member used
    std::vector<std::vector<double>> m_parameters; // their parameter values (the kernels' p)
    bool m_left_chart = false;  // the last segment stopped at a sample to change chart (not failed)
    std::size_t m_current = 0;  // the form integrating now (index into m_compiled)
    std::size_t m_switches = 0; // changes of chart so far
    bool m_start_in_body = false;
    std::vector<double> m_times;
    sample_states m_samples; // form: index into m_compiled
    std::size_t m_next_sample = 0;
    std::optional<any_method<double>> m_method;
    std::optional<split_runner> m_split;   // split2/4/6: the body form as a split system
    std::optional<sensitivity_run> m_sens; // y (+) S integrated: the scene's sensitivities
    integration_result<double> m_last;
    event_set<double, Eigen::VectorXd> m_events; // the scene's events, across chart switches
    std::vector<sample> m_event_samples;         // the state at each event (form: its own)
    std::optional<run_actions> m_actions;        // counts, time events, actions (actions.hpp)
    struct pending {
        double t;
        std::size_t index;
        bool acts; // false: an occurrence before its `after`-th, the run goes on unchanged
    };
    std::optional<pending> m_pending; // the event that ended the segment, for act()
    std::vector<std::pair<std::size_t, sample>> m_segments; // after each action: its first
                                                            // sample and the state after it
    run_result m_result;
};

// The member's exact start (prepared_scene::exact_start, GiNaC under the lock): the inertia
// tensor, the parameter values and the initial kinematics at this member's values.
initial_kinematics scene_run::exact_start() {
    decide_chart();
    member_start start = m_prepared.exact_start(m_values);
    m_inertia = start.inertia;
    check_physical_inertia(m_scene, m_inertia);
    m_model_parameters = std::move(start.model_parameters);
    start_wheel_states(m_scene, m_model_parameters, start.k0); // torque-driven wheels' p
    if (m_scene.initial == initial_kind::momenta && !start.k0.have_rates)
        throw user_error(m_scene.initial_where,
                         "momenta cannot give the rates at " + singular_words(m_angles) +
                             " (the mass matrix is singular there); give body omega1..3 "
                             "instead");
    return start.k0;
}

void scene_run::set_up_events() {
    for (const event_spec& e : m_scene.events) {
        m_events.add({}, direction_of(e), m_actions->terminal(m_result.event_names.size()), e.name);
        m_result.event_names.push_back(e.name);
    }
}

// The events' g are the compiled functions of the form integrating now; their signs and last
// times carry over a chart switch (events.hpp).
void scene_run::use_event_functions(const compiled_form& cf) {
    for (std::size_t i = 0; i < m_events.size(); ++i)
        m_events.set_function(i, [g = cf.events[i], p = m_parameters[m_current].data()](
                                     double t, const Eigen::VectorXd& y) {
            double out = 0;
            g(p, t, y.data(), &out);
            return out;
        });
}

// The events found by the last segment (hits from `from` on), with the state where each occurred,
// from each event's `after`-th occurrence on. A terminal event that stopped it either ends the run
// (a stop), or is m_pending: an action, or an occurrence before its `after`-th (no change).
void scene_run::collect_events(std::size_t from) {
    const auto& hits = m_events.hits();
    std::optional<std::size_t> stop;
    for (std::size_t h = from; h < hits.size(); ++h) {
        const std::size_t i = hits[h].index;
        if (!m_actions->occurs(i)) continue;
        note_event(hits[h].t, hits[h].y, i, m_scene.events[i].acts() ? "before" : "");
        if (m_scene.events[i].acts()) m_pending = pending{hits[h].t, i, true};
        if (m_scene.events[i].stop) stop = i;
    }
    const auto& hidden = m_events.may_hide();
    for (std::size_t h = m_result.event_doubts.size(); h < hidden.size(); ++h)
        m_result.event_doubts.push_back({hidden[h].index, hidden[h].from, hidden[h].to});
    if (m_last.code != status::stopped_by_event) return;
    if (stop) m_pending.reset();
    if (stop) return end_at_event(*stop);
    if (!m_pending) m_pending = pending{hits.back().t, m_events.stopped_by(), false};
}

void scene_run::note_event(double t, const Eigen::VectorXd& y, std::size_t index,
                           const char* phase) {
    m_event_samples.push_back({t, y, m_current});
    m_result.event_index.push_back(index);
    m_result.event_phase.push_back(phase);
}

// The run ended at the terminal event `which`, the last one noted: its state ends the rows.
void scene_run::end_at_event(std::size_t which) {
    m_result.stopped_by = static_cast<int>(which);
    const sample& e = m_event_samples.back();
    if (m_samples.empty() || m_samples.last_t() != e.t) m_samples.add(e.t, e.y, e.form);
}

// A start near the singularity starts in the body form (when the chart can switch).
void scene_run::decide_chart() {
    const form_kind form = m_scene.form;
    const bool euler_form = form != form_kind::body;
    const double sin_theta0 = is_rotor_form(form) ? std::abs(std::sin(m_values.angles[1]))
                                                  : chart_distance(m_sequence, m_values.angles[1]);
    if (euler_form && sin_theta0 < 1e-10 && !m_prepared.can_switch() && is_rotor_form(form))
        throw user_error(m_scene.initial_where, rotor_pole_message(m_values.angles[1]));
    if (euler_form && sin_theta0 < 1e-10 && !m_prepared.can_switch())
        throw user_error(
            m_scene.initial_where,
            "initial " + m_angles.names[1] + " = " + format_number(m_values.angles[1]) +
                " is the gimbal-lock singularity of the Euler-angle forms (" +
                distance_words(m_angles) + " = 0); use form: body" +
                (form == form_kind::reduced || !m_scene.switch_chart
                     ? ""
                     : " (this model's body form goes through the Euler-angle chart too)"));
    m_start_in_body = euler_form && m_prepared.can_switch() && sin_theta0 < switch_below;
    if (m_start_in_body)
        m_result.chart_note = "started in the " + std::string(to_string(other_chart(form))) +
                              " form (initial " + distance_label(m_angles) + " = " +
                              short_number(sin_theta0) + " < " + short_number(switch_below) + ")";
}

// The prepared kernels of `form` (compiled on first use), made current.
const compiled_form& scene_run::compile(form_kind form) {
    for (std::size_t i = 0; i < m_compiled.size(); ++i)
        if (m_compiled[i]->form == form) {
            m_current = i;
            return *m_compiled[i];
        }
    m_current = m_compiled.size();
    m_compiled.push_back(&m_prepared.compiled(form, m_timings, &m_result.kernels_cached));
    m_parameters.emplace_back();
    return *m_compiled.back();
}

// Integrates the current form from t_from over the remaining sample times, and says where to go
// on: the Euler-angle forms leave for the body form at a sample with |sin theta| < switch_below,
// or when the integration fails with the state that close to the singularity (only then: a
// run that exhausts max_steps elsewhere just stops); the body form returns to the scene's form at
// a sample with |sin theta| > switch_back_above.
scene_run::next scene_run::integrate_segment(Eigen::VectorXd& y, double t_from) {
    const compiled_form& cf = *m_compiled[m_current];
    const loaded_system sys = m_sens ? m_sens->system() : cf.system(m_parameters[m_current]);
    const bool can_switch = m_prepared.can_switch();
    const bool euler_chart = cf.form == form_kind::lagrangian ||
                             cf.form == form_kind::hamiltonian || cf.form == form_kind::rotor;
    std::vector<double> times(m_times.begin() + static_cast<std::ptrdiff_t>(m_next_sample),
                              m_times.end());
    const auto at = m_actions->next_time(t_from, m_scene.t_end); // a time event ends the segment
    if (at) times.erase(std::lower_bound(times.begin(), times.end(), at->first), times.end());
    if (at) times.push_back(at->first);
    const std::size_t first_sample = m_samples.size(), samples = times.size() - (at ? 1 : 0);
    // returning false stops the run at this sample: the chart is left there
    const auto observe = [&](double t, const Eigen::VectorXd& yt) {
        if (m_samples.size() == first_sample + samples) return true; // the time event's time
        m_samples.add(t, yt, m_current);
        if (m_on_sample) m_on_sample(t);
        if (!can_switch || m_samples.size() <= first_sample + 1 || reached_end(m_scene, t))
            return true;
        return euler_chart ? !sin_theta_below(m_sequence, cf.form, yt, switch_below)
                           : !(sin_theta_of(m_sequence, cf.form, yt) > switch_back_above);
    };
    const std::size_t first_hit = m_events.hits().size();
    if (m_events.size() > 0) use_event_functions(cf);
    const error_layout own = tolerance_layout(cf.f.state, m_scene); // step_control.hpp
    const error_layout layout = m_sens ? m_sens->layout(own) : own;
    if (m_method) std::visit([&](auto& m) { use_layout(m, layout); }, *m_method);
    m_timings.time("integrate", to_string(cf.form), [&] {
        m_last = m_split ? m_split->integrate(sys, t_from, y, times, observe,
                                              m_events.size() > 0 ? &m_events : nullptr, layout)
                 : m_events.size() > 0
                     ? integrate(sys, *m_method, t_from, y, times, observe, m_events)
                     : integrate(sys, *m_method, t_from, y, times, observe);
    });
    collect_events(first_hit);
    m_left_chart = m_last.code == status::stopped_by_observer;
    add_stats(m_result.stats, m_last.stats);
    if (at && m_last.ok() && m_actions->occurs(at->second)) {
        const event_spec& e = m_scene.events[at->second];
        note_event(at->first, y, at->second, e.acts() ? "before" : "");
        if (e.stop) end_at_event(at->second);
        if (e.stop) return next::done;
        m_pending = pending{at->first, at->second, e.acts()};
    }
    if (at && m_last.ok() && !m_pending) m_pending = pending{at->first, at->second, false};
    if (m_pending) return next::act;
    if (m_last.code == status::stopped_by_event) return next::done;
    if (!can_switch || m_samples.empty() || reached_end(m_scene, m_samples.last_t()))
        return next::done;
    if (m_left_chart) return euler_chart ? next::body : next::euler;
    return euler_chart && !m_last.ok() && sin_theta_of(m_sequence, cf.form, y) < switch_below
               ? next::body
               : next::done;
}

// The event m_pending ended the last segment with the state y: the state after its action (if it
// acts), formed as `initial:` forms a start (run/actions.hpp), in the body form when the
// Euler-angle chart cannot hold it; the integration restarts there. False when the action cannot
// form a state: the run stops, its message located at the event.
bool scene_run::act(Eigen::VectorXd& y, double& t_from) {
    const pending p = *m_pending;
    m_pending.reset();
    t_from = p.t;
    m_next_sample = m_samples.size();
    if (!p.acts) return true;
    const compiled_form& cf = *m_compiled[m_current];
    Eigen::VectorXd dydt(y.size());
    cf.system(m_parameters[m_current]).rhs(p.t, y.data(), dydt.data());
    const action_outcome a =
        m_actions->apply(p.index, {cf.form, p.t, y, dydt}, m_inertia, m_model_parameters);
    if (!a.error.empty()) {
        m_last.code = status::invalid_argument, m_last.message = a.error, m_last.t = p.t;
        return false;
    }
    const double d = chart_distance(m_sequence, static_cast<double>(a.k.q[1]));
    const bool in_body = cf.form != m_scene.form, can = m_prepared.can_switch();
    const bool body = can && (in_body ? d <= switch_back_above : d < switch_below);
    const compiled_form& next = compile(body ? other_chart(m_scene.form) : m_scene.form);
    y = state_of(next.f, a.k);
    m_parameters[m_current] =
        form_parameter_values(m_scene, m_model_parameters, next.f.parameters, a.k);
    note_event(p.t, y, p.index, "after");
    m_segments.push_back({m_samples.size(), m_event_samples.back()});
    ++m_result.segments;
    return true;
}

// Continues from the last sample in the other chart.
void scene_run::switch_chart(next to, Eigen::VectorXd& y, double& t_from) {
    const std::size_t k_last = m_samples.size() - 1;
    if (m_sens) refuse_sensitivity_switch(m_scene, m_samples.t(k_last));
    const sample last{m_samples.t(k_last), m_samples.y(k_last), m_samples.form(k_last)};
    const compiled_form& from = *m_compiled[m_current];
    initial_kinematics k; // a rotor changes chart directly (rotor_other_chart)
    const form_kind target = to == next::body ? other_chart(m_scene.form) : m_scene.form;
    if (!is_rotor_form(target) && to == next::body) {
        Eigen::VectorXd dydt(last.y.size());
        from.system(m_parameters[m_current]).rhs(last.t, last.y.data(), dydt.data());
        k = continuation(m_sequence, last.y, dydt);
    } else if (!is_rotor_form(target)) {
        k = from_body(m_sequence, last.y, m_inertia);
    }
    carry_wheel_states(m_scene, from.f, last.y, k);
    const double st = sin_theta_of(m_sequence, from.form, last.y);
    const std::string failed = is_rotor_form(target) ? "; the run in the first chart failed: "
                                                     : "; the Euler-angle run failed: ";
    const std::string why = !m_left_chart      ? failed + m_last.message
                            : to == next::body ? " < " + short_number(switch_below)
                                               : " > " + short_number(switch_back_above);
    if (m_switches++ == 0)
        m_result.chart_note +=
            std::string(m_result.chart_note.empty() ? "" : "; ") + "switched to the " +
            to_string(target) + " form at t = " + short_number(last.t) + " (" +
            (is_rotor_form(target) || is_rotor_form(from.form) ? std::string("|sin theta|")
                                                               : distance_label(m_angles)) +
            " = " + short_number(st) + why + ")";
    const compiled_form& next_form = compile(target);
    y = is_rotor_form(target) ? rotor_other_chart(from.form, last.y) : state_of(next_form.f, k);
    m_parameters[m_current] =
        form_parameter_values(m_scene, m_model_parameters, next_form.f.parameters, k);
    t_from = last.t;
    m_next_sample = m_samples.size();
}

// The row (t, the recorded columns) at a sample; `out` gets the record program's outputs there.
std::vector<double> scene_run::record_row(double t, Eigen::Ref<const Eigen::VectorXd> y,
                                          std::size_t form, std::vector<double>& out) const {
    const compiled_form& cf = record_outputs(t, y, form, out);
    std::optional<std::array<double, 3>> e;
    std::vector<double> row;
    row.reserve(cf.columns.size() + 1);
    row.push_back(t);
    for (const auto& src : cf.columns)
        row.push_back(source_value(m_sequence, src, y, out, m_inertia, e));
    return row;
}

// The record program's outputs at a sample, into `out`; returns the form's kernels.
const compiled_form& scene_run::record_outputs(double t, Eigen::Ref<const Eigen::VectorXd> y,
                                               std::size_t form, std::vector<double>& out) const {
    const compiled_form& cf = *m_compiled[form];
    out.resize(cf.outputs);
    cf.record(m_parameters[form].data(), t, y.data(), out.data());
    return cf;
}

// Records and invariants at every sample (and event), each by the form that integrated it; the
// rows of every sample, or of the last only (prepared_scene::every_row).
void scene_run::record() {
    const std::vector<invariant>& invariants = m_prepared.invariants();
    m_result.invariants.clear();
    for (const auto& inv : invariants)
        m_result.invariants.push_back({inv, 0, 0});
    std::vector<double> out; // the record program's outputs at a sample
    for (std::size_t e = 0; e < m_event_samples.size(); ++e) {
        const sample& s = m_event_samples[e];
        m_result.event_rows.push_back(record_row(s.t, s.y, s.form, out));
        if (m_sens) m_sens->record_event(m_result.event_index[e], s.t, s.y, m_result);
    }
    const bool every = m_prepared.every_row();
    const std::size_t n = m_samples.size() - (m_result.ok ? 0 : 1); // !ok: the last, no row
    m_result.rows.reserve(every ? n : 1);
    std::vector<double> ref(invariants.size()); // at the start of the segment (the drifts')
    const auto invariants_at = [&](double t, const Eigen::Ref<const Eigen::VectorXd>& y,
                                   std::size_t form, bool row) {
        if (row) m_result.rows.push_back(record_row(t, y, form, out));
        const compiled_form& cf = row ? *m_compiled[form] : record_outputs(t, y, form, out);
        std::optional<std::array<double, 3>> e;
        std::vector<double> v(invariants.size());
        for (std::size_t i = 0; i < invariants.size(); ++i)
            v[i] = source_value(m_sequence, cf.invariants[i], y, out, m_inertia, e);
        return v;
    };
    for (std::size_t k = 0, segment = 0; k < m_samples.size(); ++k) {
        for (; segment < m_segments.size() && m_segments[segment].first == k; ++segment) {
            const sample& s = m_segments[segment].second; // the state after an action
            ref = invariants_at(s.t, s.y, s.form, false);
        }
        const std::vector<double> v = invariants_at(
            m_samples.t(k), m_samples.y(k), m_samples.form(k), k < n && (every || k + 1 == n));
        for (std::size_t i = 0; i < invariants.size(); ++i) {
            invariant_drift& d = m_result.invariants[i];
            if (k == 0) d.first = ref[i] = v[i];
            d.drift = std::max(d.drift, std::abs(v[i] - ref[i]));
            d.largest = std::max(d.largest, std::abs(v[i]));
        }
    }
    if (m_sens) m_sens->record(m_samples, n, every, m_result);
}

// The integrator of the scene, with its step bound (a split method: the body form as a split
// system, its model checked at this member's inertia).
void scene_run::start_method() {
    const integrator_spec& ig = m_scene.integrator;
    if (is_split_method(ig.method)) {
        check_split_model(m_scene, m_inertia);
        m_split.emplace(m_scene, m_inertia);
        return;
    }
    m_method = make_method<double>(ig.method, ig.rtol, ig.atol, ig.fixed_step() ? ig.step : 0.0);
    if (!m_method) throw std::logic_error("run: unknown method " + ig.method);
    std::visit([&](auto& m) { m.max_steps = ig.max_steps; }, *m_method);
    if (auto* r = std::get_if<rodas4<double>>(&*m_method))
        r->autonomous = !m_scene.model.has_torque;
}

// The start of the run: the member's exact start, its form's kernels, the method, the state in
// that form (checked finite); returns the state.
Eigen::VectorXd scene_run::start() {
    initial_kinematics k0 = exact_start();
    m_result.record = m_scene.record;
    const compiled_form& first =
        compile(m_start_in_body ? other_chart(m_scene.form) : m_scene.form);
    if (m_scene.from && !m_start_in_body) check_start_row(*m_scene.from, first.f);
    if (m_scene.from && m_scene.form == form_kind::body) // the attitude as written, not the angles'
        k0.quat = Eigen::Quaternion<long double>(
            row_value(*m_scene.from, "q0"), row_value(*m_scene.from, "q1"),
            row_value(*m_scene.from, "q2"), row_value(*m_scene.from, "q3"));
    for (const auto& name : m_scene.record)
        for (const auto& c : record_columns(name))
            m_result.columns.push_back(c);
    m_result.form = first.form;
    m_result.state_size = first.f.state.size();
    start_method();
    m_times = sample_times(m_scene);
    m_samples.reserve(m_times.size(), first.f.state.size());
    m_actions.emplace(m_scene, m_sequence, m_model_parameters);
    set_up_events();

    Eigen::VectorXd y = state_of(first.f, k0);
    m_parameters[m_current] =
        form_parameter_values(m_scene, m_model_parameters, first.f.parameters, k0);
    check_finite_start({m_scene, m_prepared.invariants(), m_sequence, m_inertia}, k0, first,
                       m_parameters[m_current], y);
    if (m_scene.sensitivities.active()) { // the run integrates y (+) S
        m_sens.emplace(m_prepared, m_values, first, m_parameters[m_current], k0);
        y = m_sens->augmented(y);
    }
    if (m_split) {
        const integrator_spec& ig = m_scene.integrator;
        m_result.chart_note =
            "body form (quaternion, omega) for " + ig.method +
            (ig.step > 0 ? ", fixed step " + short_number(ig.step)
                         : ", steps under error control (step doubling) at rtol " +
                               short_number(ig.rtol) + ", atol " + short_number(ig.atol));
    }
    return y;
}

run_result scene_run::run() {
    Eigen::VectorXd y = start();
    double t_from = m_scene.t_start;
    for (next to = next::body; to != next::done;) {
        to = integrate_segment(y, t_from);
        if (to == next::act)
            to = act(y, t_from) ? next::body : next::done;
        else if (to != next::done)
            switch_chart(to, y, t_from);
    }
    if (!m_last.ok() && m_last.code != status::stopped_by_event) // where it stopped: its drifts
        m_samples.add(m_last.t, y, m_current);                   // count, no row (record())
    return finish();
}

// Whether the first segment's observer goes on past its sample number `sample` at (t, y), as in
// integrate_segment (false: the run changes chart there).
bool scene_run::keeps_chart(std::size_t sample, double t, const Eigen::VectorXd& y) const {
    if (!m_prepared.can_switch() || sample == 0 || reached_end(m_scene, t)) return true;
    const form_kind form = m_compiled[m_current]->form;
    const bool euler_chart = form == form_kind::lagrangian || form == form_kind::hamiltonian;
    const double st = sin_theta_of(m_sequence, form, y);
    return !(euler_chart ? st < switch_below : st > switch_back_above);
}

// The run's records from the samples of a whole run in the first form, integrated elsewhere.
run_result scene_run::finish_from(const sample_states& samples, const step_stats& stats,
                                  std::vector<member_event> events, int stopped_by) {
    for (std::size_t k = 0; k < samples.size(); ++k)
        m_samples.add(samples.t(k), samples.y(k), m_current);
    for (member_event& e : events)
        note_event(e.t, e.y, e.index, "");
    m_last = {};
    m_last.code = stopped_by >= 0 ? status::stopped_by_event : status::ok;
    if (stopped_by >= 0) end_at_event(static_cast<std::size_t>(stopped_by));
    m_last.stats = stats;
    add_stats(m_result.stats, stats);
    return finish();
}

run_result scene_run::finish() {
    if (m_switches > 1)
        m_result.chart_note +=
            "; " + std::to_string(m_switches) + " changes of chart in all (to the " +
            to_string(other_chart(m_scene.form)) + " form below " + short_number(switch_below) +
            ", back above " + short_number(switch_back_above) + ")";
    m_result.ok = m_last.ok() || m_last.code == status::stopped_by_event;
    m_result.message = m_last.message;
    m_result.integrate_seconds = m_timings.total("integrate");
    m_result.t_reached = m_samples.empty() ? m_scene.t_start : m_samples.last_t();
    record();
    return std::move(m_result); // the run's last act: its rows are not copied
}

// A member's run in parts: scene_run's start, chart test and records.
class run_in_parts : public member_parts {
  public:
    run_in_parts(const prepared_scene& prepared, const member_values& values,
                 stage_timings& timings)
        : m_values(values), m_run(prepared, m_values, timings, m_no_callback) {}
    bool start(Eigen::VectorXd& y0, std::vector<double>& parameters) override {
        y0 = m_run.start();
        parameters = m_run.parameters();
        return !m_run.starts_in_body();
    }
    bool keeps_chart(std::size_t sample, double t, const Eigen::VectorXd& y) const override {
        return m_run.keeps_chart(sample, t, y);
    }
    run_result finish(const sample_states& samples, const step_stats& stats,
                      std::vector<member_event> events, int stopped_by) override {
        return m_run.finish_from(samples, stats, std::move(events), stopped_by);
    }

  private:
    member_values m_values;
    sample_callback m_no_callback;
    scene_run m_run;
};

} // namespace

std::unique_ptr<member_parts> run_parts(const prepared_scene& prepared, const member_values& values,
                                        stage_timings& timings) {
    return std::make_unique<run_in_parts>(prepared, values, timings);
}

member_values values_of(const scene_spec& scene) {
    return {scene.angles, scene.initial_rates, scene.parameters};
}

run_result run_member(const prepared_scene& prepared, const member_values& values,
                      stage_timings& timings, const sample_callback& on_sample) {
    return scene_run(prepared, values, timings, on_sample).run();
}

run_result run_scene(const scene_spec& scene, stage_timings& timings,
                     const sample_callback& on_sample) {
    const prepared_scene prepared(scene, timings);
    return run_member(prepared, values_of(scene), timings, on_sample);
}

} // namespace rotgen
