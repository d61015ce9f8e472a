// rotgen — spec/: `body: {pivot, parts}`, the inertia from parts (model_reader, spec_detail.hpp):
// each part's kind and fields, masses and sizes checked at the parameters' defaults, then the
// tensor about the pivot from inertia/ (combine_parts) and the physical checks.
#include "spec/spec_detail.hpp"

#include "expr/numbers.hpp"

#include <algorithm>
#include <map>
#include <sstream>

namespace rotgen::spec_detail {

using GiNaC::ex;

// body: {pivot: [x, y, z], parts: [{kind: {fields}}, ...]} -> the tensor about the pivot
// (inertia.hpp: central tensors, rotation (5.44), parallel-axis shift, sum).
void model_reader::read_body(const YAML::Node& n) {
    if (!n.IsMap())
        throw user_error(at(n), "'body' must be a mapping {pivot: [x, y, z], parts: [...]}");
    check_keys(n, {"pivot", "parts"}, m_file, "body");
    std::optional<vector3> pivot;
    if (n["pivot"]) pivot = vector(n["pivot"], "body pivot", "a list of three coordinates");
    const YAML::Node parts = n["parts"];
    if (!parts) throw user_error(at(n), "'body' needs 'parts'");
    if (!parts.IsSequence() || parts.size() == 0)
        throw user_error(at(parts),
                         "body 'parts' must be a non-empty list of parts (" + kind_list() + ")");
    for (const YAML::Node& item : parts)
        m_spec.parts.push_back(read_part(item));
    m_spec.body = combine_parts(m_spec.parts, pivot, m_spec.parameter_defaults());
    m_spec.inertia = m_spec.body->tensor;
    set_diagonal_flag();
    check_physical(n, "the inertia of 'body'");
}

std::string model_reader::kind_list() {
    std::string s;
    for (const auto& k : part_kind_names())
        s += (s.empty() ? "" : ", ") + k;
    return s;
}

namespace {

// The fields each kind of part needs, and those it may have.
const std::map<part_kind, std::vector<std::string>>& required_fields() {
    static const std::map<part_kind, std::vector<std::string>> required{
        {part_kind::point, {"mass", "at"}},
        {part_kind::box, {"mass", "size", "at"}},
        {part_kind::rod, {"mass", "length", "at", "axis"}},
        {part_kind::cylinder, {"mass", "radius", "length", "at", "axis"}},
        {part_kind::sphere, {"mass", "radius", "at"}}};
    return required;
}

const std::map<part_kind, std::vector<std::string>>& optional_fields() {
    static const std::map<part_kind, std::vector<std::string>> optional{
        {part_kind::point, {}},
        {part_kind::box, {"rotation"}},
        {part_kind::rod, {}},
        {part_kind::cylinder, {}},
        {part_kind::sphere, {"hollow"}}};
    return optional;
}

} // namespace

// One part: a mapping with one key, its kind, whose value maps the part's fields.
part model_reader::read_part(const YAML::Node& item) const {
    if (!item.IsMap() || item.size() != 1)
        throw user_error(at(item), "a part must be one of " + kind_list() +
                                       " with its fields, e.g. '- box: {mass: m, size: [a, b, c], "
                                       "at: [x, y, z]}'");
    const auto kv = *item.begin();
    const std::string kind = kv.first.Scalar();
    const auto& kinds = part_kind_names();
    const auto found = std::find(kinds.begin(), kinds.end(), kind);
    if (found == kinds.end()) {
        const std::string best = closest_name(kind, kinds);
        throw user_error(at(kv.first), "unknown part '" + kind + "' (expected " + kind_list() +
                                           ")" +
                                           (best.empty() ? "" : "; did you mean '" + best + "'?"));
    }
    part p;
    p.kind = static_cast<part_kind>(found - kinds.begin());
    p.where = at(kv.first);
    const YAML::Node f = kv.second;
    std::vector<std::string> allowed = required_fields().at(p.kind);
    const auto& optional = optional_fields().at(p.kind);
    allowed.insert(allowed.end(), optional.begin(), optional.end());
    if (!f.IsMap()) {
        std::string fields;
        for (const auto& k : allowed)
            fields += (fields.empty() ? "" : ", ") + k + ": ...";
        throw user_error(at(f.IsNull() ? kv.first : f),
                         "a " + kind + " needs a mapping of its fields {" + fields + "}");
    }
    check_keys(f, allowed, m_file, "the " + kind);
    for (const auto& key : required_fields().at(p.kind))
        if (!f[key])
            throw user_error(at(kv.first), "the " + kind + " needs '" + key + "'" +
                                               (key == "at" ? " (its centre in body axes)" : ""));
    read_part_fields(f, kind, p);
    return p;
}

// The fields of a part of kind p.kind (present, as check_keys and read_part made sure).
void model_reader::read_part_fields(const YAML::Node& f, const std::string& kind, part& p) const {
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
}

// Three expressions in the parameters.
vector3 model_reader::vector(const YAML::Node& n, const std::string& what,
                             const std::string& expected) const {
    if (!n.IsSequence() || n.size() != 3) throw user_error(at(n), what + " must be " + expected);
    vector3 v;
    for (std::size_t i = 0; i < 3; ++i)
        v[i] = expression(n[i], m_names, what);
    return v;
}

// A mass (positive) or a size (not negative) with the parameters' defaults.
ex model_reader::bounded(const YAML::Node& n, const std::string& what, bool positive) const {
    const ex e = expression(n, m_names, what);
    const auto value = value_at(e, m_spec.parameter_defaults());
    if (!value)
        throw user_error(at(n),
                         what + " is not a finite real number with the parameters' defaults");
    const double v = *value;
    if (positive ? !(v > 0) : v < 0)
        throw user_error(
            at(n), what + " must be " + (positive ? "positive" : "non-negative") +
                       (GiNaC::is_a<GiNaC::numeric>(e) ? "" : " (with the parameters' defaults)") +
                       ", got " + format_value(v));
    return e;
}

std::string model_reader::format_value(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}
} // namespace rotgen::spec_detail
