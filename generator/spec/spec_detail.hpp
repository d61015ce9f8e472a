// rotgen — spec/: what the files of the model reader share (not part of the stage's interface):
// the checks on scalars (identifiers, decimal numbers), the double-precision evaluation the
// generated kernels would do, and the model_reader class whose members are defined in
// model_reader.cpp (name, parameters, potential, forces), inertia_input.cpp (the `inertia:` field
// and the physical checks) and body_parts.cpp (`body: {pivot, parts}`).
#pragma once

#include "spec/spec.hpp"

#include <optional>
#include <string>

namespace rotgen::spec_detail {

// A C++-style identifier of at most 255 characters (matched by hand: libstdc++'s std::regex
// recurses once per character and overflows the stack on a long scalar).
bool is_identifier(const std::string& s);
// A finite decimal number, the whole scalar, not subnormal; its value in `value`.
bool parse_number(const std::string& text, double& value);
// The value of e at `values` in double precision, as the generated kernels compute it; NaN when
// it is not a real number.
double double_value(const GiNaC::ex& e, const GiNaC::exmap& values);

class model_reader {
  public:
    model_reader(const std::string& file, const std::string& source);
    model_spec read(const YAML::Node& root);

  private:
    source_location at(const YAML::Node& n) const { return location_of(n, m_file); }

    // model_reader.cpp: scalars and expressions, name, parameters, potential, forces
    const YAML::Node& scalar(const YAML::Node& n, const std::string& what) const;
    GiNaC::ex expression(const YAML::Node& n, const name_table& names,
                         const std::string& what) const;
    bool finite_at_generic_state(const GiNaC::ex& e) const;
    void read_name(const YAML::Node& root);
    void read_parameters(const YAML::Node& params);
    void check_keys_unique(const YAML::Node& map, const std::string& what) const;
    name_table angle_names() const;
    void read_potential(const YAML::Node& root);
    gravity_spec read_gravity(const YAML::Node& g) const;
    void read_forces(const YAML::Node& root);

    // angles_input.cpp: `angles:` (the Euler sequence and the angles' names)
    void read_angles(const YAML::Node& root);

    // rotor_input.cpp: a linear rotor's moment and potential, and what a rotor cannot take
    void read_rotor(const YAML::Node& root);

    // wheels_input.cpp: `wheels:` (axes, moments, drives; free wheels' momenta as parameters)
    void read_wheels(const YAML::Node& n);
    wheel_spec read_wheel(const YAML::Node& item, std::vector<std::string>& taken) const;
    void read_drive(const YAML::Node& d, wheel_spec& w) const;

    // inertia_input.cpp: the tensor given directly, and the checks every tensor passes
    void read_inertia(const YAML::Node& n);
    void set_diagonal_flag();
    void check_physical(const YAML::Node& n, const std::string& what);

    // body_parts.cpp: the tensor from parts
    void read_body(const YAML::Node& n);
    static std::string kind_list();
    part read_part(const YAML::Node& item) const;
    void read_part_fields(const YAML::Node& f, const std::string& kind, part& p) const;
    vector3 vector(const YAML::Node& n, const std::string& what, const std::string& expected) const;
    GiNaC::ex bounded(const YAML::Node& n, const std::string& what, bool positive) const;
    static std::string format_value(double v);

    std::string m_file;
    model_spec m_spec;
    name_table m_names; // parameters
};

} // namespace rotgen::spec_detail
