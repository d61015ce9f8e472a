// rotgen — inspect/: a linear rotor's equations (derive/rotor.hpp) for the printers of inspect.cpp.
#include "derive/rotor.hpp"
#include "expr/symbols.hpp"
#include "inspect/equations.hpp"

namespace rotgen {

equations rotor_equations(const model_spec& spec) {
    const rotor_derivation d = derive_rotor(spec, 1);
    const auto& s = symbols();
    equations e = equations_of(d, 2, {d.q[0], d.q[1]}, {s.p[0], s.p[1]}, spec.angles);
    const GiNaC::ex phi = d.q[0], theta = d.q[1];
    // n = (sin theta sin phi, -sin theta cos phi, cos theta): the third row of A (5.25)
    e.direction = {GiNaC::sin(theta) * GiNaC::sin(phi), -GiNaC::sin(theta) * GiNaC::cos(phi),
                   GiNaC::cos(theta)};
    e.coordinates_note = "phi, theta (a linear rotor, Example 5.4: the angles of its line, body "
                         "axis 3 of z-x-z Euler angles; singular at theta = 0, pi)";
    e.latex_note = "a linear rotor: the angles \\phi, \\theta of its line (z-x-z); singular at "
                   "\\theta = 0, \\pi";
    return e;
}

} // namespace rotgen
