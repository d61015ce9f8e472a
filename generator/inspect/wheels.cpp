// rotgen — inspect/: a gyrostat's wheels (derive/wheels.hpp) in `rotgen inspect`: each wheel's
// axis, moment, drive and axial momentum, and (with --inertia) the stability of a steady spin about
// each principal axis with the wheels' momentum h along it (inertia/gyrostat.hpp).
#include "inspect/wheels.hpp"

#include "derive/wheels.hpp"
#include "expr/print.hpp"
#include "expr/symbols.hpp"
#include "inertia/gyrostat.hpp"
#include "inspect/inspect.hpp"
#include "support/format.hpp"

#include <sstream>

namespace rotgen {

namespace {

std::string drive_text(const wheel_spec& w, const angle_convention& c) {
    switch (w.drive) {
    case wheel_spec::drive_kind::rate:
        return "rate " + w.name + "_dot = " + to_text(w.drive_value, c);
    case wheel_spec::drive_kind::torque:
        return "torque " + to_text(w.drive_value, c);
    case wheel_spec::drive_kind::free:
        break;
    }
    return "free (p_" + w.name + " conserved, a parameter)";
}

// p_k = J (a . omega + alpha_dot) written with the symbols omega1..3.
std::string momentum_text(const wheel_spec& w, const angle_convention& c) {
    const auto& s = symbols();
    GiNaC::ex a = 0;
    for (int i = 0; i < 3; ++i)
        a += w.axis[i] * s.omega[i];
    const GiNaC::ex rate = w.drive == wheel_spec::drive_kind::rate
                               ? w.drive_value
                               : GiNaC::ex(GiNaC::realsymbol(w.name + "_dot"));
    return to_text(w.inertia, c) + " * (" + to_text(a, c) + " + " + to_text(rate, c) + ")";
}

} // namespace

std::string wheels_text(const model_spec& spec) {
    if (spec.wheels.empty()) return "";
    const angle_convention& c = spec.angles;
    std::ostringstream os;
    os << "\nwheels (a gyrostat; the inertia above excludes their axial moments J a a^T):\n";
    for (const wheel_spec& w : spec.wheels)
        os << "  " << w.name << ": axis (" << to_text(w.axis[0], c) << ", " << to_text(w.axis[1], c)
           << ", " << to_text(w.axis[2], c) << "), J = " << to_text(w.inertia, c) << ", drive "
           << drive_text(w, c) << "\n"
           << "    p_" << w.name << " = " << momentum_text(w, c) << "\n";
    const wheel_terms t = wheel_terms_of(spec);
    os << "  h = sum p_k a_k = (" << to_text(t.h[0], c) << ", " << to_text(t.h[1], c) << ", "
       << to_text(t.h[2], c) << ")\n"
       << "  T above is the total kinetic energy (body and wheels); L is Routh's function, the\n"
       << "  free wheels' angles eliminated (cyclic: their momenta p_k are parameters);\n"
       << "  Euler: I omega_dot + omega x (I omega + h) = tau - h_dot\n";
    if (t.torqued)
        os << "  torque-driven wheels: p_k' = tau_k, states of the run (the parameters p_k are\n"
           << "  their initial values); the body feels -tau_k a_k (in f; not in p_dot: p includes "
              "h)\n";
    return os.str();
}

std::string wheels_json(const model_spec& spec) {
    if (spec.wheels.empty()) return "";
    const angle_convention& c = spec.angles;
    std::ostringstream os;
    os << ",\n  \"wheels\": [";
    int k = 0;
    for (const wheel_spec& w : spec.wheels) {
        const char* drive = w.drive == wheel_spec::drive_kind::rate     ? "rate"
                            : w.drive == wheel_spec::drive_kind::torque ? "torque"
                                                                        : "free";
        os << (k++ ? ", " : "") << "{\"name\": " << json_quote(w.name) << ", \"axis\": ["
           << json_quote(to_text(w.axis[0], c)) << ", " << json_quote(to_text(w.axis[1], c)) << ", "
           << json_quote(to_text(w.axis[2], c))
           << "], \"inertia\": " << json_quote(to_text(w.inertia, c))
           << ", \"drive\": " << json_quote(drive);
        if (w.drive != wheel_spec::drive_kind::free)
            os << ", \"" << drive << "\": " << json_quote(to_text(w.drive_value, c));
        os << "}";
    }
    os << "]";
    return os.str();
}

std::string gyrostat_stability_text(const model_spec& spec, const inertia_report& r) {
    if (spec.wheels.empty()) return "";
    const angle_convention& c = spec.angles;
    std::ostringstream os;
    os << "\nwith the wheels: spin omega about principal axis s and wheel momentum h along it,\n"
       << "stable when (I_s + h/omega - I_j)(I_s + h/omega - I_k) > 0 (I without J a a^T);\n"
       << "unstable for h/omega strictly between the two thresholds:\n";
    for (const gyrostat_band& b : gyrostat_stability(r.principal, spec.parameter_defaults()))
        os << "  axis " << b.axis << ": unstable for " << to_text(b.low, c) << " < h/omega < "
           << to_text(b.high, c) << "  (" << format_double(b.low_value) << " .. "
           << format_double(b.high_value) << ")"
           << (b.low_value < 0 && b.high_value > 0
                   ? ": unstable bare (intermediate axis); stable once h/omega > " +
                         format_double(b.high_value) + " or < " + format_double(b.low_value)
                   : "")
           << "\n";
    return os.str();
}

std::string gyrostat_stability_json(const model_spec& spec, const inertia_report& r) {
    if (spec.wheels.empty()) return "";
    const angle_convention& c = spec.angles;
    std::ostringstream os;
    os << ",\n    \"gyrostat_stability\": [";
    int k = 0;
    for (const gyrostat_band& b : gyrostat_stability(r.principal, spec.parameter_defaults()))
        os << (k++ ? ", " : "") << "{\"axis\": " << b.axis
           << ", \"unstable_from\": " << json_quote(to_text(b.low, c))
           << ", \"unstable_to\": " << json_quote(to_text(b.high, c))
           << ", \"unstable_from_value\": " << format_double(b.low_value)
           << ", \"unstable_to_value\": " << format_double(b.high_value) << "}";
    os << "]";
    return os.str();
}

} // namespace rotgen
