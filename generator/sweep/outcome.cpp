#include "sweep/outcome.hpp"

#include "run/sensitivity_start.hpp"
#include "support/format.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace rotgen {

namespace {

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s)
        q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

} // namespace

summary_layout layout_of(const prepared_scene& prepared) {
    summary_layout l;
    for (const auto& name : prepared.scene().record)
        for (const auto& c : record_columns(name))
            l.columns.push_back(c);
    for (const auto& e : prepared.scene().events) {
        if (e.acts()) l.acting.push_back(l.events.size());
        l.events.push_back(e.name);
    }
    for (const auto& inv : prepared.invariants())
        l.invariants.push_back(inv.name);
    l.samples = static_cast<std::size_t>(prepared.scene().samples);
    const scene_spec& scene = prepared.scene();
    if (scene.sensitivities.active()) { // the columns the scene's form gives (compile_all: cached)
        stage_timings timings;
        bool cached = true;
        const compiled_form& cf = prepared.compiled(scene.form, timings, &cached);
        const std::vector<std::string> keys = sensitivity_key_names(scene, cf.f);
        for (std::size_t c = 0; c < cf.columns.size() && c < l.columns.size(); ++c)
            for (const auto& key : keys)
                l.sensitivities.push_back("d(" + l.columns[c] + ")/d(" + key + ")");
    }
    return l;
}

member_outcome run_one(const prepared_scene& prepared, const summary_layout& layout,
                       const member_values& values, bool keep_trajectory) {
    run_result r;
    try {
        stage_timings timings; // a member's own (the sweep reports preparation only)
        r = run_member(prepared, values, timings);
    } catch (const user_error& e) {
        member_outcome o = outcome_of(prepared, layout, {}, keep_trajectory);
        o.event_times.clear();
        o.status = e.message(); // no final values, no drifts: empty fields
        return o;
    }
    return outcome_of(prepared, layout, r, keep_trajectory);
}

member_outcome outcome_of(const prepared_scene& prepared, const summary_layout& layout,
                          const run_result& r, bool keep_trajectory) {
    member_outcome o;
    const std::size_t width = trajectory_columns(layout).size(), kept = 1 + layout.columns.size();
    const bool sensitivities = r.sensitivity_columns == layout.sensitivities;
    if (keep_trajectory)
        o.trajectory.assign(layout.samples * width, std::numeric_limits<double>::quiet_NaN());
    if (!r.rows.empty()) o.final_row = r.rows.back();
    if (!r.sensitivity_rows.empty() && sensitivities)
        o.final_sensitivities = r.sensitivity_rows.back(); // a member started in another form: none
    for (const auto& d : r.invariants)
        o.drifts.push_back(d.drift);
    o.event_times.assign(layout.events.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t k = 0; k < r.event_index.size(); ++k) { // in time order: the first counts
        const std::size_t i = r.event_index[k];
        if (i < o.event_times.size() && std::isnan(o.event_times[i]))
            o.event_times[i] = r.event_rows[k][0];
    }
    for (std::size_t a : layout.acting) {
        o.actions.push_back(0);
        for (std::size_t k = 0; k < r.event_index.size(); ++k)
            o.actions.back() += r.event_index[k] == a && r.event_phase[k] == "after" ? 1 : 0;
    }
    o.steps = r.stats.accepted;
    o.rhs_evals = r.stats.rhs_evals;
    if (!r.ok)
        o.status = "stopped at t = " +
                   format_double(r.rows.empty() ? prepared.scene().t_start : r.rows.back()[0]) +
                   ": " + r.message;
    for (std::size_t s = 0; keep_trajectory && s < r.rows.size() && s < layout.samples; ++s) {
        for (std::size_t c = 0; c < kept && c < r.rows[s].size(); ++c)
            o.trajectory[s * width + c] = r.rows[s][c];
        if (!sensitivities || s >= r.sensitivity_rows.size()) continue;
        for (std::size_t c = 0; c < layout.sensitivities.size(); ++c)
            o.trajectory[s * width + kept + c] = r.sensitivity_rows[s][c];
    }
    return o;
}

std::vector<std::string> trajectory_columns(const summary_layout& layout) {
    std::vector<std::string> c{"t"};
    c.insert(c.end(), layout.columns.begin(), layout.columns.end());
    c.insert(c.end(), layout.sensitivities.begin(), layout.sensitivities.end());
    return c;
}

void write_summary_header(std::ostream& os, const sweep_plan& plan, const summary_layout& layout) {
    os << "member";
    for (const auto& k : plan.keys)
        os << "," << k.key;
    os << ",final.t";
    for (const auto& c : layout.columns)
        os << ",final." << c;
    for (const auto& c : layout.sensitivities)
        os << ",final." << c;
    for (const auto& e : layout.events)
        os << ",event." << e;
    for (std::size_t a : layout.acting)
        os << ",actions." << layout.events[a];
    for (const auto& inv : layout.invariants)
        os << ",drift." << inv;
    os << ",steps,rhs_evals,status\n";
}

std::string summary_row_of(std::size_t m, const std::vector<double>& row,
                           const summary_layout& layout, const member_outcome& o) {
    std::string s = std::to_string(m);
    s.reserve(32 * (row.size() + layout.columns.size() + layout.invariants.size() + 4));
    // ",x" for the i-th of `values` if it has one and it is not NaN (where NaN means none), else
    // ","
    const auto field = [&s](const std::vector<double>& values, std::size_t i, bool nan_is_none) {
        s += ',';
        if (i < values.size() && !(nan_is_none && std::isnan(values[i])))
            append_number(s, values[i]);
    };
    for (double v : row) {
        s += ',';
        append_double(s, v);
    }
    for (std::size_t c = 0; c <= layout.columns.size(); ++c)
        field(o.final_row, c, false);
    for (std::size_t c = 0; c < layout.sensitivities.size(); ++c)
        field(o.final_sensitivities, c, false);
    for (std::size_t i = 0; i < layout.events.size(); ++i)
        field(o.event_times, i, true);
    for (std::size_t i = 0; i < layout.acting.size(); ++i)
        field(o.actions, i, false);
    for (std::size_t i = 0; i < layout.invariants.size(); ++i)
        field(o.drifts, i, false);
    s += ',' + std::to_string(o.steps) + ',' + std::to_string(o.rhs_evals) + ',' +
         csv_field(o.status) + '\n';
    return s;
}

void write_summary_row(std::ostream& os, std::size_t m, const std::vector<double>& row,
                       const summary_layout& layout, const member_outcome& outcome) {
    os << summary_row_of(m, row, layout, outcome);
}

} // namespace rotgen
