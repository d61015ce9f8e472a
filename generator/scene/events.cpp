#include "scene/events.hpp"

#include "expr/print.hpp"
#include "expr/symbols.hpp"
#include "scene/event_actions.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

namespace rotgen {

namespace {

// One symbol per record name that is the same for every convention (energy, Lx, ...): made once,
// on first use, and never changed after (the scene parses events in these symbols, the run
// evaluates them by the same ones).
const std::map<std::string, GiNaC::ex>& record_symbols() {
    static const std::map<std::string, GiNaC::ex> table = [] {
        std::map<std::string, GiNaC::ex> t;
        for (const auto& r : convention_free_records())
            t.emplace(r, GiNaC::realsymbol(r));
        return t;
    }();
    return table;
}

bool is_name(const std::string& s) {
    if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
    return std::all_of(s.begin(), s.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
}

class event_reader {
  public:
    event_reader(const model_spec& model, const std::string& file)
        : m_model(model), m_names(event_names(model)), m_file(file) {}

    event_spec read(const YAML::Node& n, double t_start) {
        if (!n.IsMap())
            throw user_error(at(n), "an event must be a mapping {name, when, direction, action}");
        check_keys(n, {"name", "when", "every", "direction", "action", "after"}, m_file,
                   "an event");
        event_spec e;
        read_name(n, e);
        e.every_origin = t_start;
        scene_detail::read_event_action(n, e, m_model, m_file);
        if (!e.periodic) read_when(n, e);
        if (const YAML::Node d = n["direction"]) {
            const std::string s = d.IsScalar() ? d.Scalar() : "";
            if (s != "rising" && s != "falling" && s != "both")
                throw user_error(at(d), "event '" + e.name + "': unknown direction '" + s +
                                            "' (expected rising, falling or both)");
            e.direction = s == "rising" ? 1 : s == "falling" ? -1 : 0;
        }
        return e;
    }

  private:
    source_location at(const YAML::Node& n) const { return location_of(n, m_file); }

    void read_when(const YAML::Node& n, event_spec& e) {
        const YAML::Node when = n["when"];
        if (!when)
            throw user_error(at(n), "event '" + e.name +
                                        "' needs 'when' (an expression) or 'every' (a period)");
        e.where = at(when);
        e.when_text = when.IsScalar() ? when.Scalar() : "";
        if (e.when_text.find_first_not_of(" \t") == std::string::npos)
            throw user_error(e.where, "event '" + e.name + "': 'when' is an empty expression");
        e.when = parse_expression(e.when_text, m_names, e.where, "event '" + e.name + "'");
    }

    void read_name(const YAML::Node& n, event_spec& e) {
        const YAML::Node name = n["name"];
        if (!name) throw user_error(at(n), "an event needs 'name'");
        e.name = name.IsScalar() ? name.Scalar() : "";
        if (!is_name(e.name))
            throw user_error(at(name), "event name '" + e.name +
                                           "' must be a name: letters, digits and '_', "
                                           "not starting with a digit");
        if (!m_seen.insert(e.name).second)
            throw user_error(at(name), "event name '" + e.name + "' is used twice");
    }

    const model_spec& m_model;
    name_table m_names;
    std::string m_file;
    std::set<std::string> m_seen;
};

} // namespace

name_table event_names(const model_spec& model) {
    name_table names = model.parameter_names();
    const coordinate_symbols& s = symbols();
    const auto& q = model.angles.names;
    for (int i = 0; i < 3; ++i) {
        names[q[i]] = s.q[i];
        names[q[i] + "_dot"] = s.qd[i];
        names["p_" + q[i]] = s.p[i];
        names["omega" + std::to_string(i + 1)] = s.omega[i];
    }
    names["t"] = s.t;
    for (const auto& [r, symbol] : record_symbols())
        if (names.count(r) == 0 && record_columns(r).size() == 1) names[r] = symbol;
    return names;
}

name_table action_names(const model_spec& model) {
    name_table names = event_names(model);
    for (const auto& [r, symbol] : record_symbols()) {
        const auto it = names.find(r);
        if (it != names.end() && it->second.is_equal(symbol)) names.erase(it);
    }
    return names;
}

std::vector<event_spec> read_events(const YAML::Node& n, const model_spec& model,
                                    const std::string& file, double t_start) {
    if (!n) return {};
    if (!n.IsSequence() || n.size() == 0)
        throw user_error(location_of(n, file),
                         "'events' must be a list of {name, when, direction, action}");
    event_reader reader(model, file);
    std::vector<event_spec> events;
    for (const auto& item : n)
        events.push_back(reader.read(item, t_start));
    return events;
}

const char* action_name(action_kind a) {
    switch (a) {
    case action_kind::stop:
        return "stop";
    case action_kind::impulse:
        return "impulse";
    case action_kind::impulse_space:
        return "impulse_space";
    case action_kind::set:
        return "set";
    default:
        return "record";
    }
}

const char* direction_name(int direction) {
    return direction > 0 ? "rising" : direction < 0 ? "falling" : "both";
}

std::string describe_events(const std::vector<event_spec>& events, const angle_convention& angles,
                            output_format format) {
    std::ostringstream os;
    if (format == output_format::json) {
        os << "\"events\": [";
        for (std::size_t i = 0; i < events.size(); ++i)
            os << (i ? ", " : "") << "{\"name\": " << json_quote(events[i].name)
               << (events[i].periodic ? ", \"every\": " : ", \"when\": ")
               << json_quote(to_text(events[i].periodic ? events[i].every : events[i].when, angles))
               << ", \"direction\": \"" << direction_name(events[i].direction)
               << "\", \"action\": \"" << action_name(events[i].action) << "\"}";
        os << "]";
        return os.str();
    }
    const bool latex = format == output_format::latex;
    os << (latex ? "\n\\section*{Events}\n\\begin{itemize}\n" : "\nEvents (zeros of g, scene)\n");
    for (const event_spec& e : events)
        os << (latex ? "\\item " : "  ") << e.name << ": "
           << (e.periodic ? (latex ? "every $" + to_latex(e.every, angles) + "$"
                                   : "every " + to_text(e.every, angles))
               : latex    ? "$" + to_latex(e.when, angles) + " = 0$"
                          : to_text(e.when, angles) + " = 0")
           << ", " << direction_name(e.direction) << ", " << action_name(e.action) << "\n";
    if (latex) os << "\\end{itemize}\n";
    return os.str();
}

} // namespace rotgen
