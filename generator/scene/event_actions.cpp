#include "scene/event_actions.hpp"

#include "expr/expr_parse.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>

namespace rotgen::scene_detail {

namespace {

class action_reader {
  public:
    action_reader(event_spec& e, const model_spec& model, const std::string& file)
        : m_e(e), m_model(model), m_file(file), m_names(action_names(model)) {
        const auto& q = model.angles.names;
        m_attitude = {{{q[0], q[1], q[2]}, {"q0", "q1", "q2", "q3"}, {"A"}}};
        m_rates = {{{q[0] + "_dot", q[1] + "_dot", q[2] + "_dot"},
                    {"p_" + q[0], "p_" + q[1], "p_" + q[2]},
                    {"omega1", "omega2", "omega3"},
                    {"omega_x", "omega_y", "omega_z"}}};
    }

    void read_every(const YAML::Node& n) {
        m_e.where = at(n);
        const std::string text = n.IsScalar() ? n.Scalar() : "";
        const GiNaC::ex T =
            parse_expression(text, m_model.parameter_names(), m_e.where, what() + " 'every'");
        const GiNaC::ex v = GiNaC::evalf(T.subs(m_model.parameter_defaults()));
        if (!GiNaC::is_a<GiNaC::numeric>(v) || !(GiNaC::ex_to<GiNaC::numeric>(v).to_double() > 0))
            throw user_error(m_e.where,
                             what() + ": 'every' must be a period > 0 (got " + text + ")");
        m_e.periodic = true;
        m_e.every = T;
        m_e.when = GiNaC::ex(1); // the event kernels' g: never zero (the run stops at its times)
        m_e.when_text.clear();
    }

    void read_after(const YAML::Node& n) {
        const std::string s = n.IsScalar() ? n.Scalar() : "";
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        if (s.empty() || *end != '\0' || !(v >= 1) || v != std::floor(v) || v > 1e15)
            throw user_error(at(n),
                             what() + ": 'after' must be a whole number >= 1 (got '" + s + "')");
        m_e.after = static_cast<long>(v);
    }

    void read_action(const YAML::Node& a) {
        m_e.action_where = at(a);
        if (a.IsScalar() && (a.Scalar() == "stop" || a.Scalar() == "record")) {
            m_e.stop = a.Scalar() == "stop";
            m_e.action = m_e.stop ? action_kind::stop : action_kind::record;
            return;
        }
        if (!a.IsMap() || a.size() != 1)
            throw user_error(at(a), what() + ": unknown action '" +
                                        (a.IsScalar() ? a.Scalar() : std::string("...")) +
                                        "' (expected stop, record, {impulse: [..]}, "
                                        "{impulse_space: [..]} or {set: {name: value}})");
        check_keys(a, {"impulse", "impulse_space", "set"}, m_file, what() + "'s action");
        if (a["set"]) return read_set(a["set"]);
        const bool space = static_cast<bool>(a["impulse_space"]);
        const YAML::Node j = space ? a["impulse_space"] : a["impulse"];
        if (!j.IsSequence() || j.size() != 3)
            throw user_error(at(j), what() + ": an impulse has 3 components [J1, J2, J3] (got " +
                                        (j.IsSequence() ? std::to_string(j.size()) : "no list") +
                                        ")");
        m_e.action = space ? action_kind::impulse_space : action_kind::impulse;
        for (std::size_t i = 0; i < 3; ++i)
            m_e.impulse[i] = value(j[i]);
    }

  private:
    source_location at(const YAML::Node& x) const { return location_of(x, m_file); }
    std::string what() const { return "event '" + m_e.name + "'"; }

    GiNaC::ex value(const YAML::Node& v) const {
        const std::string text = v.IsScalar() ? v.Scalar() : "";
        if (text.find_first_not_of(" \t") == std::string::npos)
            throw user_error(at(v), what() + ": an action's value must be an expression");
        return parse_expression(text, m_names, at(v), what() + "'s action");
    }

    // The group of `groups` that holds `name` (-1: none).
    static int group_of(const std::vector<std::vector<std::string>>& groups,
                        const std::string& name) {
        for (std::size_t g = 0; g < groups.size(); ++g)
            if (std::find(groups[g].begin(), groups[g].end(), name) != groups[g].end())
                return static_cast<int>(g);
        return -1;
    }

    void read_set(const YAML::Node& s) {
        if (!s.IsMap() || s.size() == 0)
            throw user_error(at(s), what() + ": 'set' must be a mapping {name: value, ...}");
        m_e.action = action_kind::set;
        int attitude = -1, rates = -1;
        for (const auto& kv : s) {
            const std::string name = kv.first.IsScalar() ? kv.first.Scalar() : "";
            set_entry entry{name, {}, at(kv.first)};
            const int ga = group_of(m_attitude, name), gr = group_of(m_rates, name);
            if (name.rfind("parameters.", 0) == 0) {
                check_parameter(name.substr(11), entry.where);
            } else if (ga < 0 && gr < 0) {
                throw user_error(entry.where,
                                 what() + ": cannot set '" + name +
                                     "' (expected the angles, q0..q3, A, their rates, momenta, "
                                     "omega1..3, omega_x..z or parameters.<name>)");
            } else if ((ga >= 0 && attitude >= 0 && ga != attitude) ||
                       (gr >= 0 && rates >= 0 && gr != rates)) {
                throw user_error(entry.where, what() + ": '" + name +
                                                  "' is a second way of giving the " +
                                                  (ga >= 0 ? "attitude" : "angular velocity") +
                                                  "; set it one way only (as in 'initial')");
            }
            if (ga >= 0) attitude = ga;
            if (gr >= 0) rates = gr;
            if (name == "A") {
                read_matrix(kv.second, entry);
            } else {
                entry.values.push_back(value(kv.second));
            }
            m_e.set.push_back(std::move(entry));
        }
    }

    void check_parameter(const std::string& p, const source_location& where) const {
        const auto it = std::find_if(m_model.parameters.begin(), m_model.parameters.end(),
                                     [&](const parameter& x) { return x.name == p; });
        if (it == m_model.parameters.end())
            throw user_error(where, what() + ": the model has no parameter '" + p + "'");
        for (const auto& row : m_model.inertia)
            for (const auto& v : row)
                if (v.has(it->symbol))
                    throw user_error(where, what() + ": cannot set parameters." + p +
                                                ": the inertia depends on it");
    }

    void read_matrix(const YAML::Node& m, set_entry& entry) const {
        const bool ok = m.IsSequence() && m.size() == 3 &&
                        std::all_of(m.begin(), m.end(), [](const YAML::Node& r) {
                            return r.IsSequence() && r.size() == 3;
                        });
        if (!ok) throw user_error(at(m), what() + ": A must be a 3x3 list [[..], [..], [..]]");
        for (const auto& row : m)
            for (const auto& v : row)
                entry.values.push_back(value(v));
    }

    event_spec& m_e;
    const model_spec& m_model;
    const std::string& m_file;
    name_table m_names;
    std::vector<std::vector<std::string>> m_attitude, m_rates;
};

} // namespace

void read_event_action(const YAML::Node& n, event_spec& e, const model_spec& model,
                       const std::string& file) {
    action_reader r(e, model, file);
    if (n["every"] && n["when"])
        throw user_error(location_of(n["every"], file),
                         "event '" + e.name + "': give 'when' or 'every', not both");
    if (n["every"]) r.read_every(n["every"]);
    if (n["after"]) r.read_after(n["after"]);
    if (n["action"]) r.read_action(n["action"]);
    if (e.periodic && n["direction"])
        throw user_error(location_of(n["direction"], file),
                         "event '" + e.name + "': a time event ('every') has no direction");
}

} // namespace rotgen::scene_detail
