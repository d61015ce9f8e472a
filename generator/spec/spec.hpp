// rotgen — stage 1: a model file, parsed and validated.
//
// Schema (DESIGN.md "Interfaces"): name, parameters, inertia (three principal moments or a full
// symmetric 3x3 matrix in body axes, sign convention of (5.39)) or body {pivot, parts} (the
// tensor computed exactly from point masses, boxes, rods, cylinders and spheres: inertia.hpp),
// potential (any expression in phi, theta, psi and the parameters), gravity {mass, g, com}
// shorthand, damping, torque. Keys beyond these are errors. Every error is a user_error naming
// file, line and column.
//
// With `body:` the gravity shorthand may leave out `mass` (default: the parts' total mass) and
// `com` (default: the parts' centre of mass relative to the pivot; 0 when the pivot is the
// default, the centre of mass).
#pragma once

#include "expr/angles.hpp"
#include "expr/expr_parse.hpp"
#include "inertia/inertia.hpp"
#include "support/error.hpp"

#include <ginac/ginac.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace rotgen {

struct parameter {
    std::string name;
    double value = 0;        // the model's default
    std::string description; // optional
    GiNaC::realsymbol symbol;
    source_location where;
    // A free wheel's axial momentum p_<wheel> (spec/wheels_input.cpp): initial data of a run
    // (the scene's `initial`), not a model constant, so never specialised.
    bool wheel_momentum = false;
    // A torque-driven wheel's p_<wheel>: its momentum is a state of the run (p' = tau) and this
    // parameter only its initial value; the forms take the symbol as that state.
    bool wheel_state = false;
};

// A wheel (rotor) spinning about an axis fixed in the body (a gyrostat; spec/wheels_input.cpp).
// The model's inertia holds the wheels' masses and transverse moments, not J a a^T. The wheel's
// axial momentum is p = J (a . omega + alpha_dot), alpha its angle relative to the body.
struct wheel_spec {
    enum class drive_kind { free, rate, torque };
    std::string name;  // an identifier: its angle <name>, rate <name>_dot, momentum p_<name>
    vector3 axis;      // a unit vector in body axes (normalised exactly)
    GiNaC::ex inertia; // J, its moment about its axis
    drive_kind drive = drive_kind::free;
    // rate: alpha_dot(t); torque: the motor torque on the wheel about its axis. Free: 0.
    GiNaC::ex drive_value;
    GiNaC::ex momentum; // free: the parameter p_<name> (conserved); torque: the state p_<name>
    source_location where, drive_where;
};

// Uniform gravity: V = mass g (com . e_z), e_z the space vertical in body axes, i.e. the third
// column of A (5.25): (sin(theta) sin(psi), sin(theta) cos(psi), cos(theta)).
struct gravity_spec {
    GiNaC::ex mass, g;
    std::array<GiNaC::ex, 3> com; // centre of mass in body axes, relative to the fixed point
};

// matrix3, vector3: inertia.hpp

struct model_spec {
    std::string name;   // a C++ identifier: names the header and the namespace
    std::string file;   // the path it was read from (as given)
    std::string source; // the file's text, hashed into generated headers
    // `angles:` (expr/angles.hpp): the Euler sequence and the angles' names, z-x-z phi theta psi
    // by default. Every later stage takes it from here (or from the derivation, form, scene or
    // run that carries it): the names it parses and prints, the sequence it converts by.
    angle_convention angles;
    std::vector<parameter> parameters; // in file order
    matrix3 inertia;                   // body axes, symmetric
    bool inertia_diagonal = true;
    // `body:` (inertia from parts): the parts as read and what they add up to (body->tensor is
    // `inertia`); empty when the model gives `inertia:`.
    std::vector<part> parts;
    std::optional<body_inertia> body;
    GiNaC::ex potential; // the `potential:` field plus the gravity shorthand
    std::optional<gravity_spec> gravity;
    vector3 damping; // generalised force -damping[i] * q_dot[i]
    vector3 torque;  // body-frame torque, may depend on t, q, q_dot and omega (the symbols
                     // omega1..3); includes the body damping -c_i omega_i
    bool has_damping = false;
    bool has_torque = false;
    // A linear rotor (exactly one principal moment zero, exactly: a body on a line, Example 5.4):
    // `inspect --inertia` reports it; the three-angle derivation refuses it, at `rotor_where`.
    bool rotor = false;
    source_location rotor_where;
    // Its own terms (spec/rotor_input.cpp): the moment I = I2 = I3 about the fixed point, exact,
    // and the potential in phi and theta alone, the rotor's line taken as the body axis 3 of the
    // z-x-z angles, so that its direction in space is the third row of A (5.25),
    //   n = (sin theta sin phi, -sin theta cos phi, cos theta);
    // the gravity shorthand gives V = M g d cos(theta), d the distance of the centre of mass
    // along the line (n points from the fixed point towards it).
    GiNaC::ex rotor_moment, rotor_potential;
    // `wheels:` (a gyrostat), in file order; a free wheel's momentum is also a parameter.
    std::vector<wheel_spec> wheels;

    // parameter name -> symbol, for parsing further expressions (scenes) in this model's terms.
    name_table parameter_names() const;
    // symbol -> default value, for numeric evaluation.
    GiNaC::exmap parameter_defaults() const;
};

// Reads and validates a model file. Throws user_error; a scene file (one with `model:`) is refused
// with a message that says so and names `command`, the command that takes a model ("emit").
model_spec load_model(const std::string& path, const std::string& command = "this command");

// Parses a model from an already-loaded YAML mapping (inline models in scene files);
// `file` and `source` are those of the file that holds the mapping.
model_spec parse_model(const YAML::Node& node, const std::string& file, const std::string& source);

// Reads a file and parses it as YAML, turning I/O and syntax errors into user_errors.
YAML::Node load_yaml_file(const std::string& path, std::string* source_out = nullptr);

// The location of a YAML node in `file` (1-based line and column of its first character; for
// quoted scalars, of the first character inside the quotes).
source_location location_of(const YAML::Node& node, const std::string& file);

// Checks that a mapping has only `allowed` keys and none twice (yaml-cpp keeps duplicates).
void check_keys(const YAML::Node& map, const std::vector<std::string>& allowed,
                const std::string& file, const std::string& what);

} // namespace rotgen
