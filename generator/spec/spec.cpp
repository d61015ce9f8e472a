#include "spec/spec.hpp"

#include "expr/numbers.hpp"
#include "expr/symbols.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
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
    // At most 1 MiB: a model or scene is a few hundred bytes, and `model: /dev/zero` must end.
    constexpr std::size_t max_size = std::size_t(1) << 20;
    std::string source;
    char chunk[1 << 14];
    do {
        in.read(chunk, sizeof chunk);
        source.append(chunk, static_cast<std::size_t>(in.gcount()));
        if (source.size() > max_size) throw user_error({path}, "file is larger than 1 MiB");
    } while (in);
    if (in.bad()) throw user_error({path}, "cannot read file");
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

// These two match by hand: libstdc++'s std::regex recurses once per character and overflows the
// stack on a long scalar. An identifier has at most 255 characters (later stages match names
// with std::regex).
bool is_identifier(const std::string& s) {
    const auto word = [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    };
    return !s.empty() && s.size() <= 255 && !std::isdigit(static_cast<unsigned char>(s[0])) &&
           std::all_of(s.begin(), s.end(), word);
}

// [+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?
bool is_decimal(const std::string& s) {
    std::size_t i = 0;
    const auto digits = [&] {
        const std::size_t from = i;
        while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])))
            ++i;
        return i - from;
    };
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    std::size_t mantissa = digits();
    if (i < s.size() && s[i] == '.') {
        ++i;
        mantissa += digits();
    }
    if (mantissa == 0) return false;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        ++i;
        if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
        if (digits() == 0) return false;
    }
    return i == s.size();
}

// A finite decimal number, the whole scalar (YAML's own conversion accepts ".inf" and "nan"); not
// subnormal (below 2.2e-308 in magnitude): GiNaC::numeric(double) throws CLN's underflow exception.
bool parse_number(const std::string& text, double& value) {
    if (!is_decimal(text)) return false;
    value = std::strtod(text.c_str(), nullptr);
    return std::isfinite(value) && std::fpclassify(value) != FP_SUBNORMAL;
}

// The value of e at `values` in double precision, as the generated kernels compute it; NaN when
// it is not a real number. (GiNaC's evalf works in arbitrary precision: on sin(exp(exp(20))) it
// reduces an argument of 2e8 digits modulo pi and runs for minutes.)
double double_value(const ex& e, const GiNaC::exmap& values) {
    using namespace GiNaC;
    if (is_a<numeric>(e))
        return ex_to<numeric>(e).is_real() ? ex_to<numeric>(e).to_double() : std::nan("");
    if (is_a<symbol>(e)) {
        const auto it = values.find(e);
        return it == values.end() || is_a<symbol>(it->second) ? std::nan("")
                                                              : double_value(it->second, values);
    }
    std::vector<double> v;
    for (std::size_t i = 0; i < e.nops(); ++i)
        v.push_back(double_value(e.op(i), values));
    if (is_a<add>(e)) {
        double sum = 0;
        for (double x : v)
            sum += x;
        return sum;
    }
    if (is_a<mul>(e)) {
        double product = 1;
        for (double x : v)
            product *= x;
        return product;
    }
    if (is_a<power>(e)) return std::pow(v[0], v[1]);
    if (is_a<function>(e)) {
        const std::string f = ex_to<function>(e).get_name();
        if (v.size() == 2 && f == "atan2") return std::atan2(v[0], v[1]);
        if (v.size() == 1) {
            const double x = v[0];
            if (f == "sin") return std::sin(x);
            if (f == "cos") return std::cos(x);
            if (f == "tan") return std::tan(x);
            if (f == "asin") return std::asin(x);
            if (f == "acos") return std::acos(x);
            if (f == "atan") return std::atan(x);
            if (f == "sinh") return std::sinh(x);
            if (f == "cosh") return std::cosh(x);
            if (f == "tanh") return std::tanh(x);
            if (f == "exp") return std::exp(x);
            if (f == "log") return std::log(x);
            if (f == "abs") return std::fabs(x);
        }
    }
    // Anything else (pi, a function GiNaC produced while simplifying): evalf, on finite arguments.
    for (double x : v)
        if (!std::isfinite(x)) return std::nan("");
    try {
        const ex r = evalf(e.subs(values));
        if (is_a<numeric>(r) && ex_to<numeric>(r).is_real()) return ex_to<numeric>(r).to_double();
    } catch (const std::exception&) {
    }
    return std::nan("");
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
        if (!finite_at_generic_state(e))
            throw user_error(at(n), what + " is not a finite real number with the parameters' "
                                           "defaults (a division by zero or a logarithm of a "
                                           "non-positive number?)");
        return e;
    }

    bool finite_at_generic_state(const ex& e) const {
        const auto& s = symbols();
        GiNaC::exmap generic = m_spec.parameter_defaults();
        const double values[3] = {0.3, 0.7, 1.1};
        for (int i = 0; i < 3; ++i) {
            generic[s.q[i]] = float_numeric(values[i]);
            generic[s.qd[i]] = float_numeric(values[i] / 2);
        }
        generic[s.t] = float_numeric(0.5);
        try {
            return std::isfinite(double_value(e, generic));
        } catch (const std::exception&) {
            return false;
        }
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
                                                "' must be a finite number (0, or 2.2e-308 to "
                                                "1.8e308 in magnitude)");
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
        set_diagonal_flag();
        check_physical(n, "inertia");
    }

    void set_diagonal_flag() {
        m_spec.inertia_diagonal = true;
        for (std::size_t i = 0; i < 3; ++i)
            for (std::size_t j = 0; j < 3; ++j)
                if (i != j && !m_spec.inertia[i][j].is_zero()) m_spec.inertia_diagonal = false;
    }

    // body: {pivot: [x, y, z], parts: [{kind: {fields}}, ...]} -> the tensor about the pivot
    // (inertia.hpp: central tensors, rotation (5.44), parallel-axis shift, sum).
    void read_body(const YAML::Node& n) {
        if (!n.IsMap())
            throw user_error(at(n), "'body' must be a mapping {pivot: [x, y, z], parts: [...]}");
        check_keys(n, {"pivot", "parts"}, m_file, "body");
        std::optional<vector3> pivot;
        if (n["pivot"]) pivot = vector(n["pivot"], "body pivot", "a list of three coordinates");
        const YAML::Node parts = n["parts"];
        if (!parts) throw user_error(at(n), "'body' needs 'parts'");
        if (!parts.IsSequence() || parts.size() == 0)
            throw user_error(at(parts), "body 'parts' must be a non-empty list of parts (" +
                                            kind_list() + ")");
        for (const YAML::Node& item : parts)
            m_spec.parts.push_back(read_part(item));
        m_spec.body = combine_parts(m_spec.parts, pivot, m_spec.parameter_defaults());
        m_spec.inertia = m_spec.body->tensor;
        set_diagonal_flag();
        check_physical(n, "the inertia of 'body'");
    }

    static std::string kind_list() {
        std::string s;
        for (const auto& k : part_kind_names())
            s += (s.empty() ? "" : ", ") + k;
        return s;
    }

    // One part: a mapping with one key, its kind, whose value maps the part's fields.
    part read_part(const YAML::Node& item) const {
        if (!item.IsMap() || item.size() != 1)
            throw user_error(at(item),
                             "a part must be one of " + kind_list() +
                                 " with its fields, e.g. '- box: {mass: m, size: [a, b, c], "
                                 "at: [x, y, z]}'");
        const auto kv = *item.begin();
        const std::string kind = kv.first.Scalar();
        const auto& kinds = part_kind_names();
        const auto found = std::find(kinds.begin(), kinds.end(), kind);
        if (found == kinds.end()) {
            const std::string best = closest_name(kind, kinds);
            throw user_error(at(kv.first),
                             "unknown part '" + kind + "' (expected " + kind_list() + ")" +
                                 (best.empty() ? "" : "; did you mean '" + best + "'?"));
        }
        part p;
        p.kind = static_cast<part_kind>(found - kinds.begin());
        p.where = at(kv.first);
        const YAML::Node f = kv.second;
        static const std::map<part_kind, std::vector<std::string>> required{
            {part_kind::point, {"mass", "at"}},
            {part_kind::box, {"mass", "size", "at"}},
            {part_kind::rod, {"mass", "length", "at", "axis"}},
            {part_kind::cylinder, {"mass", "radius", "length", "at", "axis"}},
            {part_kind::sphere, {"mass", "radius", "at"}}};
        static const std::map<part_kind, std::vector<std::string>> optional{
            {part_kind::point, {}},
            {part_kind::box, {"rotation"}},
            {part_kind::rod, {}},
            {part_kind::cylinder, {}},
            {part_kind::sphere, {"hollow"}}};
        std::vector<std::string> allowed = required.at(p.kind);
        allowed.insert(allowed.end(), optional.at(p.kind).begin(), optional.at(p.kind).end());
        if (!f.IsMap()) {
            std::string fields;
            for (const auto& k : allowed)
                fields += (fields.empty() ? "" : ", ") + k + ": ...";
            throw user_error(at(f.IsNull() ? kv.first : f),
                             "a " + kind + " needs a mapping of its fields {" + fields + "}");
        }
        check_keys(f, allowed, m_file, "the " + kind);
        for (const auto& key : required.at(p.kind))
            if (!f[key])
                throw user_error(at(kv.first),
                                 "the " + kind + " needs '" + key + "'" +
                                     (key == "at" ? " (its centre in body axes)" : ""));
        p.mass = bounded(f["mass"], kind + " mass", true);
        p.at = vector(f["at"], kind + " 'at'", "its centre [x, y, z] in body axes");
        p.axis = {0, 0, 1};
        p.size = {0, 0, 0};
        switch (p.kind) {
        case part_kind::point:
            break;
        case part_kind::box: {
            const YAML::Node size = f["size"];
            if (!size.IsSequence() || size.size() != 3)
                throw user_error(at(size), "box 'size' must be its three edges [a, b, c]");
            for (std::size_t i = 0; i < 3; ++i)
                p.size[i] = bounded(size[i], "box size", false);
            if (f["rotation"])
                p.rotation =
                    vector(f["rotation"], "box rotation", "z-x-z Euler angles [phi, theta, psi]");
            break;
        }
        case part_kind::cylinder:
            p.radius = bounded(f["radius"], "cylinder radius", false);
            [[fallthrough]];
        case part_kind::rod: {
            p.length = bounded(f["length"], kind + " length", false);
            p.axis = vector(f["axis"], kind + " axis", "a direction [x, y, z]");
            const ex norm2 = p.axis[0] * p.axis[0] + p.axis[1] * p.axis[1] + p.axis[2] * p.axis[2];
            const auto value = value_at(norm2, m_spec.parameter_defaults());
            if (!value || *value <= 0)
                throw user_error(at(f["axis"]),
                                 "the " + kind + " axis has zero length" +
                                     std::string(GiNaC::is_a<GiNaC::numeric>(norm2.expand())
                                                     ? ""
                                                     : " with the parameters' defaults"));
            break;
        }
        case part_kind::sphere: {
            p.radius = bounded(f["radius"], "sphere radius", false);
            if (const YAML::Node h = f["hollow"]) {
                bool hollow = false;
                if (!h.IsScalar() || !YAML::convert<bool>::decode(h, hollow))
                    throw user_error(at(h), "sphere 'hollow' must be true or false");
                p.hollow = hollow;
            }
            break;
        }
        }
        return p;
    }

    // Three expressions in the parameters.
    vector3 vector(const YAML::Node& n, const std::string& what,
                   const std::string& expected) const {
        if (!n.IsSequence() || n.size() != 3)
            throw user_error(at(n), what + " must be " + expected);
        vector3 v;
        for (std::size_t i = 0; i < 3; ++i)
            v[i] = expression(n[i], m_names, what);
        return v;
    }

    // A mass (positive) or a size (not negative) with the parameters' defaults.
    ex bounded(const YAML::Node& n, const std::string& what, bool positive) const {
        const ex e = expression(n, m_names, what);
        const auto value = value_at(e, m_spec.parameter_defaults());
        if (!value)
            throw user_error(at(n),
                             what + " is not a finite real number with the parameters' defaults");
        const double v = *value;
        if (positive ? !(v > 0) : v < 0)
            throw user_error(
                at(n),
                what + " must be " + (positive ? "positive" : "non-negative") +
                    (GiNaC::is_a<GiNaC::numeric>(e) ? "" : " (with the parameters' defaults)") +
                    ", got " + format_value(v));
        return e;
    }

    static std::string format_value(double v) {
        std::ostringstream os;
        os << v;
        return os.str();
    }

    // With the parameters at their defaults the tensor must be positive definite and its principal
    // moments must satisfy the triangle inequality I1 + I2 >= I3 (and permutations).
    void check_physical(const YAML::Node& n, const std::string& what) const {
        const GiNaC::exmap defaults = m_spec.parameter_defaults();
        Eigen::Matrix3d I;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                I(i, j) = double_value(m_spec.inertia[i][j], defaults);
                if (std::isnan(I(i, j)))
                    throw user_error(at(n), what + " does not evaluate to real numbers with the "
                                                   "parameters' defaults");
                if (!std::isfinite(I(i, j)))
                    throw user_error(at(n), what + " is not finite with the parameters' defaults");
            }
        const Eigen::Vector3d m = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
        const double scale = m.cwiseAbs().maxCoeff();
        std::ostringstream moments;
        moments << "(" << m[0] << ", " << m[1] << ", " << m[2] << ")";
        if (m[0] < -1e-12 * scale)
            throw user_error(at(n), what + " is not physical: a principal moment is negative " +
                                        moments.str());
        if (!(scale > 0) || m[0] <= 1e-14 * scale)
            throw user_error(at(n),
                             what + " has a zero principal moment " + moments.str() +
                                 ": a rotor (a body on a line, section 5.5) has no Euler-angle "
                                 "equations of motion; give all three moments positive");
        if (m[0] + m[1] < m[2] * (1 - 1e-12))
            throw user_error(at(n), what + " is not physical: principal moments " + moments.str() +
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
            // With a body, mass and com default to the parts' (com relative to the pivot).
            for (const char* key : {"mass", "g", "com"})
                if (!g[key] && (std::string(key) == "g" || !m_spec.body))
                    throw user_error(at(g), std::string("gravity needs '") + key + "'");
            gravity_spec grav;
            grav.mass =
                g["mass"] ? expression(g["mass"], m_names, "gravity mass") : m_spec.body->mass;
            grav.g = expression(g["g"], m_names, "gravity g");
            if (const YAML::Node com = g["com"]) {
                if (!com.IsSequence() || com.size() != 3)
                    throw user_error(at(com), "gravity 'com' must be a list of three coordinates");
                for (std::size_t i = 0; i < 3; ++i)
                    grav.com[i] = expression(com[i], m_names, "gravity com");
            } else {
                for (std::size_t i = 0; i < 3; ++i)
                    grav.com[i] =
                        canonical_fraction(m_spec.body->centre_of_mass[i] - m_spec.body->pivot[i],
                                           m_spec.parameter_defaults());
            }
            const auto& s = symbols();
            // e_z, the space vertical in body axes: the third column of A (5.25).
            const vector3 ez{GiNaC::sin(s.q[1]) * GiNaC::sin(s.q[2]),
                             GiNaC::sin(s.q[1]) * GiNaC::cos(s.q[2]), GiNaC::cos(s.q[1])};
            ex height = 0;
            for (int i = 0; i < 3; ++i) height += grav.com[i] * ez[i];
            m_spec.potential += grav.mass * grav.g * height;
            if (!finite_at_generic_state(m_spec.potential))
                throw user_error(at(g),
                                 "the potential with gravity is not a finite real number with "
                                 "the parameters' defaults");
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
    for (const auto& p : parameters) m[p.symbol] = float_numeric(p.value);
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
