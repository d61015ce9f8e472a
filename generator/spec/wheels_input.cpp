// rotgen — spec/: `wheels:`, symmetric wheels spinning about axes fixed in the body (a gyrostat).
//
//   wheels:
//     - name: wheel          # an identifier: angle <name>, rate <name>_dot, momentum p_<name>
//       axis: [0, 0, 1]      # body axes; normalised exactly (a / |a|), refused when zero
//       inertia: J           # the wheel's moment about its axis (positive at the defaults)
//       drive: free          # free (default) | {rate: "Omega(t)"} | {torque: "tau"}
//
// The model's inertia holds the wheels' masses and transverse moments but not J a a^T. A free
// wheel's axial momentum p = J (a . omega + alpha_dot) is conserved: it becomes the parameter
// p_<name> (default 0), initial data that a scene's `initial` or `parameters` sets. A `rate`
// drive prescribes alpha_dot(t). A `torque` drive's p_<name> is a state of the run (p' = tau): the
// parameter p_<name> (wheel_state) is its initial value, and the symbol names the state.
#include "spec/spec_detail.hpp"

#include "expr/symbols.hpp"

#include <set>

namespace rotgen::spec_detail {

using GiNaC::ex;

void model_reader::read_wheels(const YAML::Node& n) {
    if (m_spec.rotor)
        throw user_error(at(n), "model '" + m_spec.name +
                                    "' is a linear rotor (Example 5.4): rotgen models no wheels "
                                    "on a body on a line");
    if (!n.IsSequence() || n.size() == 0)
        throw user_error(at(n), "'wheels' must be a list of {name, axis, inertia, drive}");
    std::vector<std::string> taken;
    for (const auto& p : m_spec.parameters)
        taken.push_back(p.name);
    for (const auto& q : m_spec.angles.names)
        for (const std::string& s : {q, q + "_dot", "p_" + q})
            taken.push_back(s);
    for (const auto& item : n) {
        wheel_spec w = read_wheel(item, taken);
        if (w.drive != wheel_spec::drive_kind::rate) {
            const bool free = w.drive == wheel_spec::drive_kind::free;
            parameter p;
            p.name = "p_" + w.name;
            p.description = free ? "axial momentum of the free wheel '" + w.name + "' (conserved)"
                                 : "initial axial momentum of the torque-driven wheel '" + w.name +
                                       "' (a state of the run)";
            p.symbol = GiNaC::realsymbol(p.name);
            p.where = w.where;
            p.wheel_momentum = true;
            p.wheel_state = !free;
            w.momentum = p.symbol;
            m_names[p.name] = p.symbol;
            m_spec.parameters.push_back(p);
        } else {
            w.momentum = 0;
        }
        m_spec.wheels.push_back(w);
    }
}

wheel_spec model_reader::read_wheel(const YAML::Node& item, std::vector<std::string>& taken) const {
    if (!item.IsMap()) throw user_error(at(item), "a wheel must be {name, axis, inertia, drive}");
    check_keys(item, {"name", "axis", "inertia", "drive"}, m_file, "a wheel");
    for (const char* key : {"name", "axis", "inertia"})
        if (!item[key]) throw user_error(at(item), std::string("a wheel needs '") + key + "'");
    wheel_spec w;
    const YAML::Node name = item["name"];
    w.where = at(name);
    if (!name.IsScalar() || !is_identifier(name.Scalar()))
        throw user_error(w.where, "a wheel's name must be an identifier (letters, digits, _)");
    w.name = name.Scalar();
    if (const std::string why = reserved_reason(w.name, m_spec.angles); !why.empty())
        throw user_error(w.where, "'" + w.name + "' cannot name a wheel: " + why);
    for (const std::string& s : {w.name, w.name + "_dot", "p_" + w.name})
        for (const auto& t : taken)
            if (s == t)
                throw user_error(w.where, "the wheel '" + w.name + "' gives the name '" + s +
                                              "', which is already taken (a parameter, an "
                                              "angle's name or another wheel)");
    for (const std::string& s : {w.name, w.name + "_dot", "p_" + w.name})
        taken.push_back(s);
    const YAML::Node a = item["axis"];
    if (!a.IsSequence() || a.size() != 3)
        throw user_error(at(a), "a wheel's 'axis' must be a list of three components");
    ex norm2 = 0;
    for (std::size_t i = 0; i < 3; ++i) {
        w.axis[i] = expression(a[i], m_names, "wheel axis");
        norm2 += w.axis[i] * w.axis[i];
    }
    const double n2 = double_value(norm2, m_spec.parameter_defaults());
    if (!(n2 > 1e-300)) throw user_error(at(a), "the axis of wheel '" + w.name + "' is zero");
    const ex norm = GiNaC::sqrt(norm2.expand());
    if (!(norm - 1).expand().is_zero())
        for (auto& c : w.axis)
            c = c / norm;
    w.inertia = expression(item["inertia"], m_names, "wheel inertia");
    if (!(double_value(w.inertia, m_spec.parameter_defaults()) > 0))
        throw user_error(at(item["inertia"]), "the inertia of wheel '" + w.name +
                                                  "' (its moment about its axis) must be positive");
    w.drive_value = 0;
    if (item["drive"]) read_drive(item["drive"], w);
    return w;
}

// free | {rate: expr in t} | {torque: expr in t, the angles, their rates, omega1..3}
void model_reader::read_drive(const YAML::Node& d, wheel_spec& w) const {
    w.drive_where = at(d);
    const std::string kinds = "free, {rate: expression of t} or {torque: expression}";
    if (d.IsScalar()) {
        if (d.Scalar() != "free")
            throw user_error(w.drive_where, "unknown drive '" + d.Scalar() + "' of wheel '" +
                                                w.name + "': expected " + kinds);
        return;
    }
    if (!d.IsMap() || d.size() != 1)
        throw user_error(w.drive_where, "the drive of wheel '" + w.name + "' must be " + kinds);
    check_keys(d, {"rate", "torque"}, m_file, "the drive of wheel '" + w.name + "'");
    name_table names = m_names;
    const auto& s = symbols();
    names["t"] = s.t;
    if (d["rate"]) {
        w.drive = wheel_spec::drive_kind::rate;
        w.drive_value = expression(d["rate"], names, "wheel rate");
        w.drive_where = at(d["rate"]);
        return;
    }
    names = angle_names();
    names["t"] = s.t;
    for (int i = 0; i < 3; ++i) {
        names[m_spec.angles.names[i] + "_dot"] = s.qd[i];
        names["omega" + std::to_string(i + 1)] = s.omega[i];
    }
    w.drive = wheel_spec::drive_kind::torque;
    w.drive_value = expression(d["torque"], names, "wheel torque");
    w.drive_where = at(d["torque"]);
}

} // namespace rotgen::spec_detail
