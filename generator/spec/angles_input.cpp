// rotgen — spec/: `angles:`, the model's Euler-angle sequence and the names of its angles
// (expr/angles.hpp):
//   angles: zyx                                       # default names for the sequence
//   angles: {sequence: zyx, names: [yaw, pitch, roll]}
// Absent: the chapter's z-x-z (phi, theta, psi). The convention read is the model's
// (model_spec::angles: the names every later stage parses and prints, passed down with the
// model); it is read before the parameters, so that a parameter cannot take an angle's name.
#include "spec/spec_detail.hpp"

#include "expr/angles.hpp"
#include "expr/symbols.hpp"

#include <set>

namespace rotgen::spec_detail {

namespace {
const char* const sequences = "zxz zyz xyx xzx yxy yzy (proper Euler) or zyx zxy yxz yzx xyz xzy "
                              "(Tait-Bryan)";
} // namespace

void model_reader::read_angles(const YAML::Node& root) {
    angle_convention c; // the chapter's unless this model says otherwise
    m_spec.angles = c;
    const YAML::Node n = root["angles"];
    if (!n) return;
    // (no Node is assigned twice: yaml-cpp's assignment writes through to the node it refers to)
    if (n.IsMap()) {
        check_keys(n, {"sequence", "names"}, m_file, "angles");
        if (!n["sequence"]) throw user_error(at(n), "'angles' needs 'sequence' (for example zyx)");
    } else if (!n.IsScalar()) {
        throw user_error(at(n), "'angles' must be a sequence such as zyx, or {sequence: zyx, "
                                "names: [yaw, pitch, roll]}");
    }
    const YAML::Node seq = n.IsMap() ? n["sequence"] : n;
    const bool named = n.IsMap() && n["names"];
    const YAML::Node names = named ? n["names"] : n;
    const auto axes = seq.IsScalar() ? parse_sequence(seq.Scalar()) : std::nullopt;
    if (!axes)
        throw user_error(at(seq), "unknown Euler sequence '" +
                                      (seq.IsScalar() ? seq.Scalar() : "") + "': one of " +
                                      sequences);
    c.axes = *axes;
    c.names = default_angle_names(c.axes);
    if (named) {
        if (!names.IsSequence() || names.size() != 3)
            throw user_error(at(names), "angle 'names' must be a list of three names");
        std::set<std::string> seen;
        for (std::size_t i = 0; i < 3; ++i) {
            const YAML::Node x = names[i];
            const std::string name = x.IsScalar() ? x.Scalar() : "";
            if (!is_identifier(name) || name.size() > 32)
                throw user_error(at(x), "angle name '" + name + "' is not an identifier");
            if (!seen.insert(name).second)
                throw user_error(at(x), "angle name '" + name + "' is given twice");
            c.names[i] = name;
        }
    }
    for (std::size_t i = 0; i < 3; ++i) {
        // the chapter's names are reserved for the coordinates whatever their order; any other
        // reserved name (a function, a constant, a C++ keyword, omega1, t) is refused
        const std::string& name = c.names[i];
        if (name == "phi" || name == "theta" || name == "psi") continue;
        if (const std::string why = reserved_reason(name, angle_convention{}); !why.empty())
            throw user_error(at(named ? names[i] : seq),
                             "'" + name + "' cannot name an angle: " + why);
    }
    m_spec.angles = c;
}

} // namespace rotgen::spec_detail
