// rotgen — derive/: a gyrostat's wheel terms (wheels.hpp).
#include "derive/wheels.hpp"

#include "expr/symbols.hpp"
#include "support/error.hpp"

namespace rotgen {

using GiNaC::ex;
using drive = wheel_spec::drive_kind;

namespace {

ex axial(const wheel_spec& w, const vector3& omega) {
    ex a = 0;
    for (int i = 0; i < 3; ++i)
        a += w.axis[i] * omega[i];
    return a;
}

} // namespace

wheel_terms wheel_terms_of(const model_spec& spec) {
    const ex t = symbols().t;
    wheel_terms r;
    for (int i = 0; i < 3; ++i)
        r.h[i] = r.h_driven[i] = r.h_dot[i] = r.motor[i] = 0;
    for (const wheel_spec& w : spec.wheels) {
        r.any = true;
        if (w.drive == drive::rate) {
            r.driven = true;
            const ex omega = w.drive_value,
                     omega_dot = w.drive_value.diff(GiNaC::ex_to<GiNaC::symbol>(t));
            for (int i = 0; i < 3; ++i) {
                r.h_driven[i] += w.inertia * omega * w.axis[i];
                r.h[i] += w.inertia * omega * w.axis[i];
                r.h_dot[i] += w.inertia * omega_dot * w.axis[i];
            }
            r.kinetic += w.inertia * omega * omega / 2;
            r.routh += w.inertia * omega * omega / 2;
        } else { // free or torque-driven: p_k a parameter or a state
            if (w.drive == drive::torque) r.torqued = true;
            for (int i = 0; i < 3; ++i) {
                r.h[i] += w.momentum * w.axis[i];
                if (w.drive == drive::torque) r.motor[i] -= w.drive_value * w.axis[i];
            }
            r.kinetic += w.momentum * w.momentum / (2 * w.inertia);
            r.routh -= w.momentum * w.momentum / (2 * w.inertia);
        }
    }
    return r;
}

matrix3 gyrostat_inertia(const model_spec& spec) {
    matrix3 I = spec.inertia;
    for (const wheel_spec& w : spec.wheels)
        if (w.drive == drive::rate)
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    I[i][j] = (I[i][j] + w.inertia * w.axis[i] * w.axis[j]).expand();
    return I;
}

std::vector<std::string> wheel_record_names(const model_spec& spec) {
    if (spec.wheels.empty()) return {};
    std::vector<std::string> names{"h1", "h2", "h3"};
    for (const wheel_spec& w : spec.wheels) {
        names.push_back(w.name + "_dot");
        names.push_back("p_" + w.name);
    }
    return names;
}

model_spec gyrostat_body(const model_spec& spec) {
    model_spec b = spec;
    bool driven = false;
    for (const wheel_spec& w : spec.wheels)
        driven = driven || w.drive == drive::rate;
    if (!driven) return b;
    b.inertia = gyrostat_inertia(spec);
    bool diagonal = true;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            diagonal = diagonal && (i == j || b.inertia[i][j].is_zero());
    b.inertia_diagonal = diagonal;
    return b;
}

std::vector<ex> wheel_momenta(const model_spec& spec, const vector3& omega) {
    std::vector<ex> p;
    for (const wheel_spec& w : spec.wheels)
        p.push_back(w.drive == drive::rate ? w.inertia * (axial(w, omega) + w.drive_value)
                                           : w.momentum);
    return p;
}

std::vector<ex> wheel_rates(const model_spec& spec, const vector3& omega) {
    std::vector<ex> r;
    for (const wheel_spec& w : spec.wheels)
        r.push_back(w.drive == drive::rate ? w.drive_value
                                           : w.momentum / w.inertia - axial(w, omega));
    return r;
}

void refuse_torque_wheels(const model_spec& spec, const std::string& what,
                          const std::string& instead) {
    for (const wheel_spec& w : spec.wheels)
        if (w.drive == drive::torque)
            throw user_error(w.drive_where, "wheel '" + w.name + "' has a torque drive, which " +
                                                what + " does not take (its momentum p_" + w.name +
                                                " is a state of the run); " + instead);
}

std::vector<ex> wheel_torques(const model_spec& spec) {
    std::vector<ex> r;
    for (const wheel_spec& w : spec.wheels)
        if (w.drive == drive::torque) r.push_back(w.drive_value);
    return r;
}

std::vector<const wheel_spec*> torque_wheels(const model_spec& spec) {
    std::vector<const wheel_spec*> r;
    for (const wheel_spec& w : spec.wheels)
        if (w.drive == drive::torque) r.push_back(&w);
    return r;
}

} // namespace rotgen
