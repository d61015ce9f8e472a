// rotgen — spec/: model_reader, the reader of one model mapping (spec_detail.hpp): the order of
// the fields, expressions and their finiteness at a generic state, the name, the parameters, the
// potential with the gravity shorthand, damping and torque. The inertia is read by
// inertia_input.cpp and body_parts.cpp.
#include "spec/spec_detail.hpp"

#include "expr/angles.hpp"
#include "expr/numbers.hpp"
#include "expr/symbols.hpp"

#include <cmath>
#include <set>

namespace rotgen::spec_detail {

using GiNaC::ex;

model_reader::model_reader(const std::string& file, const std::string& source) : m_file(file) {
    m_spec.file = file;
    m_spec.source = source;
}

model_spec model_reader::read(const YAML::Node& root) {
    check_keys(root,
               {"name", "description", "angles", "parameters", "inertia", "body", "potential",
                "gravity", "damping", "torque", "wheels"},
               m_file, "the model");
    read_name(root);
    read_angles(root);
    if (root["parameters"]) read_parameters(root["parameters"]);
    if (root["body"] && root["inertia"])
        throw user_error(at(root["body"]), "give either 'inertia' or 'body' (the inertia from "
                                           "parts), not both");
    if (root["body"])
        read_body(root["body"]);
    else if (root["inertia"])
        read_inertia(root["inertia"]);
    else
        throw user_error({m_file, 1, 1},
                         "missing field 'inertia' (or 'body', the inertia from parts)");
    read_potential(root);
    read_forces(root);
    if (m_spec.rotor && !m_spec.angles.is_default())
        throw user_error(at(root["angles"]), "model '" + m_spec.name +
                                                 "' is a linear rotor (Example 5.4): its two "
                                                 "angles are the z-x-z phi and theta; leave "
                                                 "'angles' out");
    if (m_spec.rotor) read_rotor(root);
    if (root["wheels"]) read_wheels(root["wheels"]);
    return std::move(m_spec);
}

const YAML::Node& model_reader::scalar(const YAML::Node& n, const std::string& what) const {
    if (!n.IsScalar()) throw user_error(at(n), "expected a number or an expression for " + what);
    return n;
}

// Parses an expression and checks that it is finite with the parameters' defaults at a
// generic state (a parameter that defaults to 0 under a division would give inf at run time).
ex model_reader::expression(const YAML::Node& n, const name_table& names,
                            const std::string& what) const {
    const ex e = parse_expression(scalar(n, what).Scalar(), names, at(n), what);
    if (!finite_at_generic_state(e))
        throw user_error(at(n), what + " is not a finite real number with the parameters' "
                                       "defaults (a division by zero or a logarithm of a "
                                       "non-positive number?)");
    return e;
}

bool model_reader::finite_at_generic_state(const ex& e) const {
    const auto& s = symbols();
    GiNaC::exmap generic = m_spec.parameter_defaults();
    const double values[3] = {0.3, 0.7, 1.1};
    for (int i = 0; i < 3; ++i) {
        generic[s.q[i]] = float_numeric(values[i]);
        generic[s.qd[i]] = float_numeric(values[i] / 2);
        generic[s.omega[i]] = float_numeric(values[i] / 3);
    }
    generic[s.t] = float_numeric(0.5);
    try {
        return std::isfinite(double_value(e, generic));
    } catch (const std::exception&) {
        return false;
    }
}

void model_reader::read_name(const YAML::Node& root) {
    if (!root["name"]) throw user_error({m_file, 1, 1}, "missing field 'name'");
    const YAML::Node n = root["name"];
    if (!n.IsScalar() || !is_identifier(n.Scalar()))
        throw user_error(at(n), "the model name must be a C++ identifier (letters, digits, _)");
    if (const std::string why = reserved_reason(n.Scalar(), angle_convention{});
        !why.empty() && why.find("keyword") != std::string::npos)
        throw user_error(at(n), "the model name '" + n.Scalar() + "' is reserved: " + why);
    m_spec.name = n.Scalar();
}

void model_reader::read_parameters(const YAML::Node& params) {
    if (params.IsNull()) return;
    if (!params.IsMap())
        throw user_error(at(params), "'parameters' must be a mapping of name: default value");
    check_keys_unique(params, "parameters");
    for (const auto& kv : params) {
        parameter p;
        p.name = kv.first.Scalar();
        p.where = at(kv.first);
        if (!is_identifier(p.name))
            throw user_error(p.where, "parameter name '" + p.name + "' is not an identifier");
        if (const std::string why = reserved_reason(p.name, m_spec.angles); !why.empty())
            throw user_error(p.where, "'" + p.name + "' cannot be a parameter name: " + why);
        YAML::Node value = kv.second;
        if (value.IsMap()) {
            check_keys(value, {"value", "description"}, m_file, "parameter '" + p.name + "'");
            if (value["description"]) p.description = value["description"].as<std::string>("");
            if (!value["value"])
                throw user_error(at(value), "parameter '" + p.name + "' has no 'value'");
            value = value["value"];
        }
        if (!value.IsScalar() || !parse_number(value.Scalar(), p.value))
            throw user_error(at(value), "the default of parameter '" + p.name +
                                            "' must be a finite number (0, or 2.2e-308 to "
                                            "1.8e308 in magnitude)");
        p.symbol = GiNaC::realsymbol(p.name);
        m_names[p.name] = p.symbol;
        m_spec.parameters.push_back(p);
    }
}

// Parameters are read from a mapping whose keys check_keys cannot list in advance.
void model_reader::check_keys_unique(const YAML::Node& map, const std::string& what) const {
    std::set<std::string> seen;
    for (const auto& kv : map) {
        if (!kv.first.IsScalar())
            throw user_error(at(kv.first), "keys of " + what + " must be names");
        if (!seen.insert(kv.first.Scalar()).second)
            throw user_error(at(kv.first),
                             "duplicate field '" + kv.first.Scalar() + "' in " + what);
    }
}

name_table model_reader::angle_names() const {
    name_table names = m_names;
    const auto& s = symbols();
    for (int i = 0; i < 3; ++i)
        names[m_spec.angles.names[i]] = s.q[i];
    return names;
}

// `potential:` or the gravity shorthand's M g (com . e_z), never both.
void model_reader::read_potential(const YAML::Node& root) {
    m_spec.potential = 0;
    int seen = 0; // of `potential` and `gravity`: refused at the second one in the file
    for (const auto& kv : root)
        if (kv.first.Scalar() == "potential" || kv.first.Scalar() == "gravity")
            if (++seen == 2)
                throw user_error(at(kv.first), "give 'gravity' or 'potential', not both (gravity "
                                               "is the potential M g (com . e); write the whole "
                                               "potential in 'potential' instead)");
    if (root["potential"])
        m_spec.potential = expression(root["potential"], angle_names(), "potential");
    if (const YAML::Node g = root["gravity"]) {
        const gravity_spec grav = read_gravity(g);
        // e_z, the space vertical in body axes: the third column of A (5.25; for z-x-z
        // (sin theta sin psi, sin theta cos psi, cos theta)).
        const ex_matrix3 A = rotation_of_angles(m_spec.angles);
        ex height = 0;
        for (int i = 0; i < 3; ++i)
            height += grav.com[i] * A[i][2];
        m_spec.potential += grav.mass * grav.g * height;
        if (!finite_at_generic_state(m_spec.potential))
            throw user_error(at(g), "the potential with gravity is not a finite real number with "
                                    "the parameters' defaults");
        m_spec.gravity = grav;
    }
}

// gravity: {mass, g, com}; with a body, mass and com default to the parts' (com relative to
// the pivot).
gravity_spec model_reader::read_gravity(const YAML::Node& g) const {
    if (!g.IsMap()) throw user_error(at(g), "'gravity' must be {mass: M, g: g, com: [x, y, z]}");
    check_keys(g, {"mass", "g", "com"}, m_file, "gravity");
    for (const char* key : {"mass", "g", "com"})
        if (!g[key] && (std::string(key) == "g" || !m_spec.body))
            throw user_error(at(g), std::string("gravity needs '") + key + "'");
    gravity_spec grav;
    // a negative mass would turn gravity upside down (issue 14): positive at the defaults
    grav.mass = g["mass"] ? bounded(g["mass"], "gravity mass", true) : m_spec.body->mass;
    grav.g = expression(g["g"], m_names, "gravity g");
    if (const YAML::Node com = g["com"]) {
        if (!com.IsSequence() || com.size() != 3)
            throw user_error(at(com), "gravity 'com' must be a list of three coordinates");
        for (std::size_t i = 0; i < 3; ++i)
            grav.com[i] = expression(com[i], m_names, "gravity com");
    } else {
        for (std::size_t i = 0; i < 3; ++i)
            grav.com[i] = canonical_fraction(m_spec.body->centre_of_mass[i] - m_spec.body->pivot[i],
                                             m_spec.parameter_defaults());
    }
    return grav;
}

// damping: c, [c1, c2, c3] (the generalised force -c_i q_dot_i) or {body: [c1, c2, c3]} (the
// body-axis torque -c_i omega_i, added to the torque); torque: three body-axis components in t,
// the angles, their rates and omega1..3.
void model_reader::read_forces(const YAML::Node& root) {
    for (auto& d : m_spec.damping)
        d = 0;
    for (auto& d : m_spec.torque)
        d = 0;
    vector3 body_damping{0, 0, 0};
    if (const YAML::Node d = root["damping"]) {
        if (d.IsScalar()) {
            const ex c = expression(d, m_names, "damping");
            for (auto& di : m_spec.damping)
                di = c;
        } else if (d.IsSequence() && d.size() == 3) {
            for (std::size_t i = 0; i < 3; ++i)
                m_spec.damping[i] = expression(d[i], m_names, "damping");
        } else if (d.IsMap()) {
            check_keys(d, {"body"}, m_file, "damping");
            const YAML::Node b = d["body"];
            if (!b || !b.IsSequence() || b.size() != 3)
                throw user_error(at(b ? b : d), "damping 'body' must be a list of three "
                                                "coefficients [c1, c2, c3] (the torque "
                                                "-c_i omega_i about body axis i)");
            for (std::size_t i = 0; i < 3; ++i)
                body_damping[i] = expression(b[i], m_names, "damping");
        } else {
            throw user_error(at(d), "'damping' must be one coefficient, a list of three, or "
                                    "{body: [c1, c2, c3]}");
        }
        m_spec.has_damping = true;
    }
    if (const YAML::Node tq = root["torque"]) {
        if (!tq.IsSequence() || tq.size() != 3)
            throw user_error(at(tq), "'torque' must be a list of three body-frame components");
        name_table names = angle_names();
        const auto& s = symbols();
        names["t"] = s.t;
        for (int i = 0; i < 3; ++i) {
            names[m_spec.angles.names[i] + "_dot"] = s.qd[i];
            names["omega" + std::to_string(i + 1)] = s.omega[i];
        }
        for (std::size_t i = 0; i < 3; ++i)
            m_spec.torque[i] = expression(tq[i], names, "torque");
        m_spec.has_torque = true;
    }
    for (std::size_t i = 0; i < 3; ++i)
        if (!body_damping[i].is_zero()) {
            m_spec.torque[i] += -body_damping[i] * symbols().omega[i];
            m_spec.has_torque = true;
        }
}
} // namespace rotgen::spec_detail
