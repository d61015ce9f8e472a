// rotgen — scene/: the values a scene writes (parameter overrides and initial values), read as
// numbers or as expressions of the model language (expr/expr_parse.hpp): `theta: pi/2`,
// `psi_dot: 2*pi*f` with the model's parameters by name, standing for their values in this scene
// (the overrides, else the model's defaults). Internal to the scene stage.
//
// A plain decimal number is read as today: its double, whose exact value is later taken to be the
// shortest decimal that reads back as it (run/kinematics). An expression is kept exact (GiNaC:
// rationals, pi, functions of them; no floats) with the parameters' exact values put in, and its
// double is its value evaluated at 40 digits and rounded once.
#pragma once

#include "scene/scene.hpp"

#include <map>
#include <string>
#include <vector>

namespace rotgen::scene_detail {

// A decimal number and nothing else, finite and not subnormal (else a user_error at n naming
// `what`).
double scene_number(const YAML::Node& n, const std::string& file, const std::string& what);

class value_reader {
  public:
    value_reader(const std::string& file, const model_spec& model);

    // The parameters of the model with the scene's overrides (a mapping name: number or
    // expression, or a null node), in model order. An override may use other parameters (their
    // scene values); one that depends on itself is an error at its value.
    std::vector<written_value> parameters(const YAML::Node& overrides);

    // One value (an initial value); `what` names it in messages ("initial theta"). Parameters
    // stand for the values parameters() gave.
    written_value value(const YAML::Node& n, const std::string& what) const;

  private:
    source_location at(const YAML::Node& n) const { return location_of(n, m_file); }
    written_value evaluate(const YAML::Node& n, const std::string& what,
                           const GiNaC::exmap& values) const;
    void resolve(std::size_t i, const YAML::Node& overrides);

    std::string m_file;
    const model_spec& m_model;
    name_table m_names;                  // the model's parameters
    std::vector<written_value> m_values; // resolved so far
    std::vector<int> m_state;            // 0 not yet, 1 being resolved, 2 resolved
    GiNaC::exmap m_exact;                // parameter symbol -> exact value (resolved ones)
};

} // namespace rotgen::scene_detail
