#include "spec.hpp"

#include "symbols.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace rotgen {

using GiNaC::ex;

source_location location_of(const YAML::Node& node, const std::string& file) {
    const YAML::Mark m = node.Mark();
    source_location where{file, m.line + 1, m.column + 1};
    if (node.IsScalar() && node.Tag() == "!") where = where.shifted(1); // inside the quotes
    return where;
}

YAML::Node load_yaml_file(const std::string& path, std::string* source_out) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw user_error({path}, "cannot open file: " + std::string(std::strerror(errno)));
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw user_error({path}, "cannot read file");
    const std::string source = text.str();
    if (source_out) *source_out = source;
    try {
        YAML::Node root = YAML::Load(source);
        if (!root.IsMap())
            throw user_error({path, 1, 1}, "expected a YAML mapping at the top level");
        return root;
    } catch (const YAML::Exception& e) {
        throw user_error({path, e.mark.line + 1, e.mark.column + 1}, "malformed YAML: " + e.msg);
    }
}

void check_keys(const YAML::Node& map, const std::vector<std::string>& allowed,
                const std::string& file, const std::string& what) {
    std::set<std::string> seen;
    for (const auto& kv : map) {
        if (!kv.first.IsScalar())
            throw user_error(location_of(kv.first, file), "keys of " + what + " must be names");
        const std::string key = kv.first.Scalar();
        if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
            const std::string best = closest_name(key, allowed);
            throw user_error(location_of(kv.first, file),
                             "unknown field '" + key + "' in " + what +
                                 (best.empty() ? "" : "; did you mean '" + best + "'?"));
        }
        if (!seen.insert(key).second)
            throw user_error(location_of(kv.first, file),
                             "duplicate field '" + key + "' in " + what);
    }
}

namespace {

bool is_identifier(const std::string& s) {
    static const std::regex id("[A-Za-z_][A-Za-z0-9_]*");
    return std::regex_match(s, id);
}

// A finite decimal number, the whole scalar (YAML's own conversion accepts ".inf" and "nan").
bool parse_number(const std::string& text, double& value) {
    static const std::regex number("[+-]?([0-9]+\\.?[0-9]*|\\.[0-9]+)([eE][+-]?[0-9]+)?");
    if (!std::regex_match(text, number)) return false;
    value = std::strtod(text.c_str(), nullptr);
    return std::isfinite(value);
}

class model_reader {
  public:
    model_reader(const std::string& file, const std::string& source) : m_file(file) {
        m_spec.file = file;
        m_spec.source = source;
    }

    model_spec read(const YAML::Node& root) {
        check_keys(root,
                   {"name", "description", "parameters", "inertia", "body", "potential", "gravity",
                    "damping", "torque"},
                   m_file, "the model");
        read_name(root);
        if (root["parameters"]) read_parameters(root["parameters"]);
        if (root["body"])
            throw user_error(at(root["body"]),
                             "'body' (inertia from parts) is not supported yet; give 'inertia'");
        if (!root["inertia"]) throw user_error({m_file, 1, 1}, "missing field 'inertia'");
        read_inertia(root["inertia"]);
        read_potential(root);
        read_forces(root);
        return std::move(m_spec);
    }

  private:
    source_location at(const YAML::Node& n) const { return location_of(n, m_file); }

    const YAML::Node& scalar(const YAML::Node& n, const std::string& what) const {
        if (!n.IsScalar())
            throw user_error(at(n), "expected a number or an expression for " + what);
        return n;
    }

    // Parses an expression and checks that it is finite with the parameters' defaults at a
    // generic state (a parameter that defaults to 0 under a division would give inf at run time).
    ex expression(const YAML::Node& n, const name_table& names, const std::string& what) const {
        const ex e = parse_expression(scalar(n, what).Scalar(), names, at(n), what);
        const auto& s = symbols();
        GiNaC::exmap generic = m_spec.parameter_defaults();
        const double values[3] = {0.3, 0.7, 1.1};
        for (int i = 0; i < 3; ++i) {
            generic[s.q[i]] = values[i];
            generic[s.qd[i]] = values[i] / 2;
        }
        generic[s.t] = 0.5;
        bool finite = false;
        try {
            const ex v = GiNaC::evalf(e.subs(generic));
            finite = GiNaC::is_a<GiNaC::numeric>(v) && GiNaC::ex_to<GiNaC::numeric>(v).is_real() &&
                     std::isfinite(GiNaC::ex_to<GiNaC::numeric>(v).to_double());
        } catch (const std::exception&) {
            finite = false;
        }
        if (!finite)
            throw user_error(at(n), what + " is not a finite real number with the parameters' "
                                           "defaults (a division by zero or a logarithm of a "
                                           "non-positive number?)");
        return e;
    }

    void read_name(const YAML::Node& root) {
        if (!root["name"]) throw user_error({m_file, 1, 1}, "missing field 'name'");
        const YAML::Node n = root["name"];
        if (!n.IsScalar() || !is_identifier(n.Scalar()))
            throw user_error(at(n), "the model name must be a C++ identifier (letters, digits, _)");
        if (const std::string why = reserved_reason(n.Scalar()); !why.empty() &&
                                                                  why.find("keyword") != std::string::npos)
            throw user_error(at(n), "the model name '" + n.Scalar() + "' is reserved: " + why);
        m_spec.name = n.Scalar();
    }

    void read_parameters(const YAML::Node& params) {
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
            if (const std::string why = reserved_reason(p.name); !why.empty())
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
                                                "' must be a finite number");
            p.symbol = GiNaC::realsymbol(p.name);
            m_names[p.name] = p.symbol;
            m_spec.parameters.push_back(p);
        }
    }

    // Parameters are read from a mapping whose keys check_keys cannot list in advance.
    void check_keys_unique(const YAML::Node& map, const std::string& what) const {
        std::set<std::string> seen;
        for (const auto& kv : map) {
            if (!kv.first.IsScalar())
                throw user_error(at(kv.first), "keys of " + what + " must be names");
            if (!seen.insert(kv.first.Scalar()).second)
                throw user_error(at(kv.first),
                                 "duplicate field '" + kv.first.Scalar() + "' in " + what);
        }
    }

    void read_inertia(const YAML::Node& n) {
        const auto bad = [&] {
            return user_error(at(n), "'inertia' must be three principal moments [I1, I2, I3] or a "
                                     "symmetric 3x3 matrix [[Ixx, Ixy, Ixz], [...], [...]]");
        };
        if (!n.IsSequence() || n.size() != 3) throw bad();
        const bool full = n[0].IsSequence();
        for (std::size_t i = 0; i < 3; ++i)
            for (std::size_t j = 0; j < 3; ++j) m_spec.inertia[i][j] = 0;
        if (!full) {
            for (std::size_t i = 0; i < 3; ++i)
                m_spec.inertia[i][i] = expression(n[i], m_names, "inertia");
        } else {
            for (std::size_t i = 0; i < 3; ++i) {
                if (!n[i].IsSequence() || n[i].size() != 3) throw bad();
                for (std::size_t j = 0; j < 3; ++j)
                    m_spec.inertia[i][j] = expression(n[i][j], m_names, "inertia");
            }
            for (std::size_t i = 0; i < 3; ++i)
                for (std::size_t j = i + 1; j < 3; ++j)
                    if (!(m_spec.inertia[i][j] - m_spec.inertia[j][i]).expand().is_zero())
                        throw user_error(at(n[j][i]),
                                         "inertia is not symmetric: entry [" + std::to_string(j + 1) +
                                             "][" + std::to_string(i + 1) + "] differs from [" +
                                             std::to_string(i + 1) + "][" + std::to_string(j + 1) + "]");
        }
        m_spec.inertia_diagonal = true;
        for (std::size_t i = 0; i < 3; ++i)
            for (std::size_t j = 0; j < 3; ++j)
                if (i != j && !m_spec.inertia[i][j].is_zero()) m_spec.inertia_diagonal = false;
        check_physical(n);
    }

    // With the parameters at their defaults the tensor must be positive definite and its principal
    // moments must satisfy the triangle inequality I1 + I2 >= I3 (and permutations).
    void check_physical(const YAML::Node& n) const {
        const GiNaC::exmap defaults = m_spec.parameter_defaults();
        Eigen::Matrix3d I;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const ex v = GiNaC::evalf(m_spec.inertia[i][j].subs(defaults));
                if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
                    throw user_error(at(n), "inertia does not evaluate to real numbers with the "
                                            "parameters' defaults");
                I(i, j) = GiNaC::ex_to<GiNaC::numeric>(v).to_double();
                if (!std::isfinite(I(i, j)))
                    throw user_error(at(n), "inertia is not finite with the parameters' defaults");
            }
        const Eigen::Vector3d m = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
        const double scale = m.cwiseAbs().maxCoeff();
        std::ostringstream moments;
        moments << "(" << m[0] << ", " << m[1] << ", " << m[2] << ")";
        if (m[0] < -1e-12 * scale)
            throw user_error(at(n), "inertia is not physical: a principal moment is negative " +
                                        moments.str());
        if (!(scale > 0) || m[0] <= 1e-14 * scale)
            throw user_error(at(n), "inertia has a zero principal moment " + moments.str() +
                                        ": a rotor (a body on a line, section 5.5) has no Euler-angle "
                                        "equations of motion; give all three moments positive");
        if (m[0] + m[1] < m[2] * (1 - 1e-12))
            throw user_error(at(n), "inertia is not physical: principal moments " + moments.str() +
                                        " break the triangle inequality I1 + I2 >= I3");
    }

    name_table angle_names() const {
        name_table names = m_names;
        const auto& s = symbols();
        for (int i = 0; i < 3; ++i) names[coordinate_names()[i]] = s.q[i];
        return names;
    }

    void read_potential(const YAML::Node& root) {
        m_spec.potential = 0;
        if (root["potential"]) m_spec.potential = expression(root["potential"], angle_names(), "potential");
        if (const YAML::Node g = root["gravity"]) {
            if (!g.IsMap()) throw user_error(at(g), "'gravity' must be {mass: M, g: g, com: [x, y, z]}");
            check_keys(g, {"mass", "g", "com"}, m_file, "gravity");
            for (const char* key : {"mass", "g", "com"})
                if (!g[key]) throw user_error(at(g), std::string("gravity needs '") + key + "'");
            gravity_spec grav;
            grav.mass = expression(g["mass"], m_names, "gravity mass");
            grav.g = expression(g["g"], m_names, "gravity g");
            const YAML::Node com = g["com"];
            if (!com.IsSequence() || com.size() != 3)
                throw user_error(at(com), "gravity 'com' must be a list of three coordinates");
            for (std::size_t i = 0; i < 3; ++i) grav.com[i] = expression(com[i], m_names, "gravity com");
            const auto& s = symbols();
            // e_z, the space vertical in body axes: the third column of A (5.25).
            const vector3 ez{GiNaC::sin(s.q[1]) * GiNaC::sin(s.q[2]),
                             GiNaC::sin(s.q[1]) * GiNaC::cos(s.q[2]), GiNaC::cos(s.q[1])};
            ex height = 0;
            for (int i = 0; i < 3; ++i) height += grav.com[i] * ez[i];
            m_spec.potential += grav.mass * grav.g * height;
            m_spec.gravity = grav;
        }
    }

    void read_forces(const YAML::Node& root) {
        for (auto& d : m_spec.damping) d = 0;
        for (auto& d : m_spec.torque) d = 0;
        if (const YAML::Node d = root["damping"]) {
            if (d.IsScalar()) {
                const ex c = expression(d, m_names, "damping");
                for (auto& di : m_spec.damping) di = c;
            } else if (d.IsSequence() && d.size() == 3) {
                for (std::size_t i = 0; i < 3; ++i) m_spec.damping[i] = expression(d[i], m_names, "damping");
            } else {
                throw user_error(at(d), "'damping' must be one coefficient or a list of three");
            }
            m_spec.has_damping = true;
        }
        if (const YAML::Node tq = root["torque"]) {
            if (!tq.IsSequence() || tq.size() != 3)
                throw user_error(at(tq), "'torque' must be a list of three body-frame components");
            name_table names = angle_names();
            const auto& s = symbols();
            names["t"] = s.t;
            for (int i = 0; i < 3; ++i) names[coordinate_names()[i] + "_dot"] = s.qd[i];
            for (std::size_t i = 0; i < 3; ++i) m_spec.torque[i] = expression(tq[i], names, "torque");
            m_spec.has_torque = true;
        }
    }

    std::string m_file;
    model_spec m_spec;
    name_table m_names; // parameters
};

} // namespace

name_table model_spec::parameter_names() const {
    name_table names;
    for (const auto& p : parameters) names[p.name] = p.symbol;
    return names;
}

GiNaC::exmap model_spec::parameter_defaults() const {
    GiNaC::exmap m;
    for (const auto& p : parameters) m[p.symbol] = GiNaC::numeric(p.value);
    return m;
}

model_spec parse_model(const YAML::Node& node, const std::string& file, const std::string& source) {
    if (!node.IsMap()) throw user_error(location_of(node, file), "a model must be a YAML mapping");
    return model_reader(file, source).read(node);
}

model_spec load_model(const std::string& path) {
    std::string source;
    const YAML::Node root = load_yaml_file(path, &source);
    return parse_model(root, path, source);
}

} // namespace rotgen
