#include "scene/scene.hpp"

#include "expr/numbers.hpp"
#include "scene/initial_input.hpp"
#include "scene/rotor_scene.hpp"
#include "scene/values.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "derive/wheels.hpp"
#include "expr/angles.hpp"
#include "expr/symbols.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>

namespace rotgen {

const std::vector<std::string>& convention_free_records() {
    static const std::vector<std::string> names{
        "omega1", "omega2", "omega3", "energy", "body_x", "body_y", "body_z", "q0", "q1", "q2",
        "q3",     "Lx",     "Ly",     "Lz",     "L1",     "L2",     "L3",     "T",  "V"};
    return names;
}

// The model's angles, their rates and momenta (in c's names), then the rest.
std::vector<std::string> recordable_names(const angle_convention& c) {
    const auto& q = c.names;
    std::vector<std::string> names{q[0],          q[1],          q[2],
                                   q[0] + "_dot", q[1] + "_dot", q[2] + "_dot",
                                   "p_" + q[0],   "p_" + q[1],   "p_" + q[2]};
    const auto& rest = convention_free_records();
    names.insert(names.end(), rest.begin(), rest.end());
    return names;
}

std::vector<std::string> record_columns(const std::string& name) {
    if (name.rfind("body_", 0) == 0) return {name + "_x", name + "_y", name + "_z"};
    return {name};
}

namespace {

class scene_reader {
  public:
    scene_reader(std::string file, std::string command)
        : m_file(std::move(file)), m_command(std::move(command)) {}

    scene_spec read() {
        std::string source;
        const YAML::Node root = load_yaml_file(m_file, &source);
        refuse_model_file(root);
        check_keys(root,
                   {"model", "parameters", "form", "initial", "time", "integrator", "record",
                    "description", "switch_chart", "sweep", "events", "sensitivities"},
                   m_file, "the scene");
        m_scene.file = m_file;
        m_scene.where = {m_file, 1, 1};
        m_scene.integrator_where = m_scene.where;
        for (const char* key : {"model", "initial", "time"})
            if (!root[key])
                throw user_error({m_file, 1, 1}, std::string("missing field '") + key + "'");
        read_model(root["model"], source);
        read_parameters(root["parameters"]);
        read_form(root["form"]);
        read_initial(root);
        read_time(root["time"]);
        if (root["integrator"]) read_integrator(root["integrator"]);
        if (m_scene.model.rotor) scene_detail::check_rotor_integrator(m_scene);
        read_record(root["record"]);
        m_scene.events = read_events(root["events"], m_scene.model, m_file, m_scene.t_start);
        if (const YAML::Node sw = root["switch_chart"]) {
            if (!sw.IsScalar() || (sw.Scalar() != "true" && sw.Scalar() != "false"))
                throw user_error(at(sw), "switch_chart must be true or false");
            m_scene.switch_chart = sw.Scalar() == "true";
        }
        scene_detail::check_wheel_scene(m_scene);
        m_scene.sensitivities = read_sensitivities(root["sensitivities"], m_scene, m_file);
        return std::move(m_scene);
    }

  private:
    source_location at(const YAML::Node& n) const { return location_of(n, m_file); }

    // A model file given where a scene is expected: located at the key that makes it a model.
    void refuse_model_file(const YAML::Node& root) const {
        if (root["model"]) return;
        for (const auto& kv : root) {
            const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "";
            if (key == "inertia" || key == "body")
                throw user_error(at(kv.first), "this is a model file (it has '" + key + ":'); " +
                                                   m_command +
                                                   " takes a scene, which names its model with "
                                                   "'model:'");
        }
    }

    double number(const YAML::Node& n, const std::string& what) const {
        return scene_detail::scene_number(n, m_file, what);
    }

    void read_model(const YAML::Node& n, const std::string& source) {
        if (n.IsMap()) {
            m_scene.model = parse_model(n, m_file, source);
            m_model_root = n;
            m_model_file = m_file;
            m_model_source = source;
            return;
        }
        if (!n.IsScalar())
            throw user_error(at(n), "'model' must be a file name or a model mapping");
        std::string path = n.Scalar();
        if (!path.empty() && path[0] != '/') {
            const auto slash = m_file.find_last_of('/');
            if (slash != std::string::npos) path = m_file.substr(0, slash + 1) + path;
        }
        std::ifstream probe(path);
        if (!probe) // located at the scene's `model:` key, which names the file
            throw user_error(at(n),
                             "cannot open the model file '" + path + "': " + std::strerror(errno));
        m_model_root = load_yaml_file(path, &m_model_source);
        m_model_file = path;
        m_scene.model = parse_model(m_model_root, m_model_file, m_model_source);
    }

    // Overrides are numbers or expressions in the model's parameters (values.hpp).
    void read_parameters(const YAML::Node& n) {
        m_values.emplace(m_file, m_scene.model);
        if (n && !n.IsMap())
            throw user_error(at(n), "'parameters' must be a mapping of name: value");
        std::vector<std::string> names;
        for (const auto& p : m_scene.model.parameters)
            names.push_back(p.name);
        if (n) check_keys(n, names, m_file, "parameters (of model '" + m_scene.model.name + "')");
        m_scene.parameters_written = m_values->parameters(n);
        for (const auto& w : m_scene.parameters_written)
            m_scene.parameters.push_back(w.value);
        if (n && n.size() > 0) check_model_with_overrides(n);
    }

    // The model was checked with its defaults (finite expressions, a physical inertia); check it
    // again with the scene's values by reading it with those as its defaults (a mass of 0 under a
    // division, or a negative moment, would otherwise reach the integrator).
    void check_model_with_overrides(const YAML::Node& overrides) const {
        // A new parameters mapping (a value may be an alias shared with other nodes).
        YAML::Node values(YAML::NodeType::Map);
        for (std::size_t i = 0; i < m_scene.parameters.size(); ++i) {
            if (m_scene.model.parameters[i].wheel_momentum) continue; // the wheels' own, below
            char text[32];
            std::snprintf(text, sizeof text, "%.17g", m_scene.parameters[i]);
            values[m_scene.model.parameters[i].name] = std::string(text);
        }
        YAML::Node model = YAML::Clone(m_model_root);
        model.remove("parameters");
        model["parameters"] = values;
        try {
            (void)parse_model(model, m_model_file, m_model_source);
        } catch (const user_error& e) {
            // the model's checks speak of its defaults; here the values are the scene's
            std::string problem = e.problem();
            const std::string defaults = "the parameters' defaults";
            for (auto pos = problem.find(defaults); pos != std::string::npos;
                 pos = problem.find(defaults, pos))
                problem.replace(pos, defaults.size(), "these values");
            throw user_error(at(overrides), "with these parameter values the model (" +
                                                m_model_file + ") is not valid: " + problem);
        }
    }

    void read_form(const YAML::Node& n) {
        if (m_scene.model.rotor) m_scene.form = form_kind::rotor; // its one form, the default
        if (!n) return;
        m_scene.form_given = true;
        const std::string f = n.IsScalar() ? n.Scalar() : "";
        if (f == "lagrangian")
            m_scene.form = form_kind::lagrangian;
        else if (f == "hamiltonian")
            m_scene.form = form_kind::hamiltonian;
        else if (f == "reduced")
            m_scene.form = form_kind::reduced;
        else if (f == "body")
            m_scene.form = form_kind::body;
        else if (f == "rotor")
            m_scene.form = form_kind::rotor;
        else
            throw user_error(at(n), "unknown form '" + f +
                                        "' (expected lagrangian, hamiltonian, reduced, body or "
                                        "rotor)");
        scene_detail::check_rotor_form(m_scene, n, m_file);
    }

    // A complete state in one of the accepted ways: the angles with their rates, with the
    // momenta, or with body omega. Nothing defaults to 0.
    void read_initial(const YAML::Node& root) {
        const YAML::Node n = root["initial"];
        if (!n.IsMap()) throw user_error(at(n), "'initial' must be a mapping of angles and rates");
        m_scene.initial_where = at(n);
        if (m_scene.model.rotor)
            return scene_detail::read_rotor_initial(m_scene, n, initial_key(root), *m_values,
                                                    m_file);
        scene_detail::read_initial_state(m_scene, n, initial_key(root), *m_values, m_file);
        scene_detail::read_wheel_initial(m_scene, n, root["parameters"], *m_values, m_file);
    }

    // Where the `initial` key is written (the mapping's location if not found).
    source_location initial_key(const YAML::Node& root) const {
        source_location key = at(root["initial"]);
        for (const auto& kv : root)
            if (kv.first.IsScalar() && kv.first.Scalar() == "initial") key = at(kv.first);
        return key;
    }

    void read_time(const YAML::Node& n) {
        if (!n.IsMap()) throw user_error(at(n), "'time' must be {start, end, samples}");
        check_keys(n, {"start", "end", "samples"}, m_file, "time");
        if (!n["end"]) throw user_error(at(n), "time needs 'end'");
        m_scene.t_start = n["start"] ? number(n["start"], "time start") : 0.0;
        m_scene.t_end = number(n["end"], "time end");
        m_scene.time_where = at(n["end"]);
        if (m_scene.t_end == m_scene.t_start)
            throw user_error(at(n["end"]), "time end must differ from time start (an end "
                                           "before the start runs backward in time)");
        if (!std::isfinite(m_scene.t_end - m_scene.t_start))
            throw user_error(at(n["end"]), "the time span end - start is not a finite number");
        if (n["samples"]) {
            const double s = number(n["samples"], "time samples");
            if (s < 2 || s > 1e8 || s != std::floor(s))
                throw user_error(at(n["samples"]),
                                 "time samples must be a whole number from 2 to 1e8");
            m_scene.samples = static_cast<long>(s);
        }
    }

    void read_integrator(const YAML::Node& n) {
        if (!n.IsMap())
            throw user_error(at(n), "'integrator' must be {method, rtol, atol} or {method, step} "
                                    "(a step: fixed steps, no error control)");
        check_keys(n, {"method", "rtol", "atol", "step", "max_steps", "error"}, m_file,
                   "integrator");
        m_scene.integrator_where = at(n);
        integrator_spec& ig = m_scene.integrator;
        if (n["method"]) {
            const std::vector<std::string> methods{
                "rk4",    "dopri5", "dop853", "implicit_midpoint", "rosenbrock", "split2", "split4",
                "split6", "taylor", "auto"};
            ig.method = n["method"].Scalar();
            if (std::find(methods.begin(), methods.end(), ig.method) == methods.end()) {
                const std::string best = closest_name(ig.method, methods);
                throw user_error(
                    at(n["method"]),
                    "unknown integrator '" + ig.method +
                        "' (expected rk4, dopri5, dop853, implicit_midpoint, rosenbrock, "
                        "split2, split4, split6, taylor or auto)" +
                        (best.empty() ? "" : "; did you mean '" + best + "'?"));
            }
        }
        if (ig.method == "auto" || n["error"]) return read_auto(n);
        const auto positive = [&](const char* key, double& value) {
            if (!n[key]) return;
            value = number(n[key], std::string("integrator ") + key);
            if (!(value > 0))
                throw user_error(at(n[key]),
                                 std::string("integrator ") + key + " must be positive");
        };
        positive("rtol", ig.rtol);
        positive("atol", ig.atol);
        positive("step", ig.step);
        if (n["max_steps"]) {
            double m = 0;
            positive("max_steps", m);
            if (m < 1 || m > 1e15 || m != std::floor(m))
                throw user_error(at(n["max_steps"]),
                                 "integrator max_steps must be a whole number from 1 to 1e15");
            ig.max_steps = static_cast<long>(m);
        }
        if (ig.fixed_step() && !n["step"])
            throw user_error(at(n), "integrator " + ig.method + " is fixed-step and needs 'step'");
        if (n["step"])
            for (const char* key : {"rtol", "atol"})
                if (n[key])
                    throw user_error(at(n[key]), "integrator " + ig.method +
                                                     " with a fixed step has no error control: "
                                                     "give 'step' or '" +
                                                     key + "', not both");
        if (ig.rtol < 1e-15 && !ig.fixed_step())
            throw user_error(at(n["rtol"]),
                             "integrator rtol below 1e-15 cannot be met in double precision");
        if (ig.step > 0 && ig.step > std::abs(m_scene.t_end - m_scene.t_start))
            throw user_error(at(n["step"]), "integrator step is longer than the time span");
    }

    // integrator: {method: auto, error: 1e-8} (tune/ chooses the method before the run).
    void read_auto(const YAML::Node& n) {
        if (m_scene.integrator.method != "auto")
            throw user_error(at(n["error"]), "integrator error is the target of method auto; "
                                             "give rtol and atol to " +
                                                 m_scene.integrator.method);
        for (const char* key : {"rtol", "atol", "step"})
            if (n[key])
                throw user_error(at(n[key]), std::string("integrator auto chooses its ") + key +
                                                 " itself: give 'error' only");
        if (!n["error"])
            throw user_error(at(n), "integrator auto needs 'error': the largest error accepted "
                                    "at the samples, e.g. {method: auto, error: 1e-8}");
        const double e = number(n["error"], "integrator error");
        if (!(e > 0 && e < 1))
            throw user_error(at(n["error"]), "integrator error must be between 0 and 1");
        m_scene.integrator.error = e;
        if (n["max_steps"]) throw user_error(at(n["max_steps"]), "integrator auto sets max_steps");
    }

    void read_record(const YAML::Node& n) {
        if (!n) {
            m_scene.record = m_scene.model.rotor
                                 ? std::vector<std::string>{"phi", "theta", "energy"}
                                 : std::vector<std::string>{
                                       m_scene.model.angles.names[0], m_scene.model.angles.names[1],
                                       m_scene.model.angles.names[2], "energy"};
            m_scene.record_default = true;
            m_scene.record_where.assign(m_scene.record.size(), m_scene.where);
            return;
        }
        if (!n.IsSequence()) throw user_error(at(n), "'record' must be a list of quantities");
        if (n.size() == 0) throw user_error(at(n), "'record' must list at least one quantity");
        std::vector<std::string> allowed = recordable_names(m_scene.model.angles);
        for (const auto& w : wheel_record_names(m_scene.model)) // a gyrostat's h, p_k, rates
            allowed.push_back(w);
        for (const auto& item : n) {
            const std::string name = item.IsScalar() ? item.Scalar() : "";
            if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
                const std::string best = closest_name(name, allowed);
                throw user_error(at(item),
                                 "cannot record '" + name + "'" +
                                     (best.empty() ? "" : "; did you mean '" + best + "'?"));
            }
            if (const std::string why = scene_detail::rotor_unrecordable(name);
                m_scene.model.rotor && !why.empty())
                throw user_error(at(item),
                                 "cannot record '" + name + "' for a linear rotor: " + why);
            if (std::find(m_scene.record.begin(), m_scene.record.end(), name) !=
                m_scene.record.end())
                throw user_error(at(item), "'" + name + "' is recorded twice");
            m_scene.record.push_back(name);
            m_scene.record_where.push_back(at(item));
        }
    }

    std::string m_file;
    std::string m_command; // the command that reads the scene, for messages
    scene_spec m_scene;
    YAML::Node
        m_model_root; // the model's mapping, its file and text (for check_model_with_overrides)
    std::string m_model_file, m_model_source;
    std::optional<scene_detail::value_reader> m_values; // after the model is read
};

} // namespace

scene_spec load_scene(const std::string& path, const std::string& command) {
    return scene_reader(path, command).read();
}

scene_spec with_records(const scene_spec& scene, const std::vector<std::string>& extra) {
    scene_spec more = scene;
    for (const auto& name : extra)
        if (std::find(more.record.begin(), more.record.end(), name) == more.record.end()) {
            more.record.push_back(name);
            more.record_where.push_back(scene.where);
        }
    more.record_default = false;
    return more;
}

} // namespace rotgen
