// rotgen — spec/: a linear rotor's own terms (Example 5.4, §5.5): its moment and its potential in
// the rotor's two angles, and the fields a rotor cannot take.
//
// A body on a line has I1 = 0 along the line and I2 = I3 = I across it (inertia/rotor.cpp). Its
// attitude is the direction n of the line, two angles: with the line as the body axis 3 of the
// z-x-z Euler angles, n is the third row of A = Az(psi) Ax(theta) Az(phi) (5.25),
//   n = (sin theta sin phi, -sin theta cos phi, cos theta),
// which does not depend on psi, the turn about the line that moves no mass. So
//   T = 1/2 I (theta_dot^2 + sin^2 theta phi_dot^2),
// and a potential may depend on phi and theta only. The gravity shorthand's centre of mass c
// (relative to the fixed point) lies on the line: c = d n in space, d = |c|, and
//   V = M g (c . e_z) = M g d cos(theta),
// the direction n chosen from the fixed point towards the centre of mass (theta = pi hangs).
#include "spec/spec_detail.hpp"

#include "expr/symbols.hpp"

namespace rotgen::spec_detail {

using GiNaC::ex;

void model_reader::read_rotor(const YAML::Node& root) {
    const std::string what = "model '" + m_spec.name + "' is a linear rotor (Example 5.4)";
    for (const char* key : {"torque", "damping"})
        if (root[key])
            throw user_error(at(root[key]),
                             what + ": rotgen models no '" + key +
                                 "' on a rotor (its generalised forces act on phi and theta "
                                 "only); leave it out, or write the force as a potential in "
                                 "phi and theta");
    m_spec.rotor_moment = *exact_rotor_moment(m_spec.inertia);
    const auto& s = symbols();
    if (const YAML::Node p = root["potential"]) {
        if (m_spec.potential.has(s.q[2]))
            throw user_error(at(p), what + ": its potential may depend on phi and theta only "
                                           "(the direction of its line); psi, the turn about "
                                           "the line, is not a coordinate of a rotor");
        m_spec.rotor_potential = m_spec.potential;
        return;
    }
    m_spec.rotor_potential = 0;
    if (!m_spec.gravity) return;
    const gravity_spec& g = *m_spec.gravity;
    const std::optional<ex> arm = rotor_arm(m_spec.inertia, g.com);
    if (!arm)
        throw user_error(at(root["gravity"]),
                         what + ": the centre of mass (gravity 'com') must lie on its line (the "
                                "axis of its zero moment)");
    m_spec.rotor_potential = g.mass * g.g * *arm * GiNaC::cos(s.q[1]);
}

} // namespace rotgen::spec_detail
