// rotgen — forms/: the reduced form, the Hamiltonian form without its cyclic coordinates (Routh):
// their equations are dropped, their momenta become parameters (conserved), their rates an
// optional output `ignored_rates`. Heavy symmetric top: y = (theta, p_theta).
//
// The rates are the canonical Hamilton equations of the derivation (where identities such as
// sin^2 psi + cos^2 psi = 1 have cancelled, so that an ignored angle is really absent); the
// composed ones of hamilton() are an alternative when they do not mention an ignored angle.
#include "forms/form_algebra.hpp"

#include "expr/angles.hpp"
#include "expr/symbols.hpp"
#include "support/error.hpp"

#include <algorithm>

namespace rotgen::form_detail {

using GiNaC::ex;

namespace {

// Cyclic coordinates (absent from L and Q) that the remaining equations do not mention, in the
// canonical form. Throws user_error when there is none.
std::vector<int> ignored_coordinates(const model_spec& spec, const derivation& d) {
    const auto& s = symbols();
    std::vector<int> dropped;
    for (int i : d.cyclic) {
        bool absent = true;
        for (int k = 0; k < 3; ++k)
            absent = absent && !d.hamilton_qdot[k].has(s.q[i]) && !d.hamilton_pdot[k].has(s.q[i]);
        if (absent) dropped.push_back(i);
    }
    if (dropped.empty())
        throw user_error({spec.file},
                         "the reduced form needs a cyclic coordinate, and model '" + spec.name +
                             "' has none (damping, torques or the potential depend on every "
                             "angle or rate); use --form hamiltonian");
    return dropped;
}

bool contains(const std::vector<int>& v, int i) {
    return std::find(v.begin(), v.end(), i) != v.end();
}

// The name of the first ignored coordinate that one of `values` mentions, or "".
std::string mentioned_ignored(const std::vector<ex>& values, const std::vector<int>& dropped,
                              const angle_convention& c) {
    const auto& s = symbols();
    for (const ex& e : values)
        for (int i : dropped)
            if (e.has(s.q[i])) return c.names[i];
    return std::string();
}

// The state (kept angles, then their momenta) and its rates; returns the composed rates (the
// alternative by hamilton()'s route) in the same order.
std::vector<ex> reduced_state_and_rates(const derivation& d, const hamilton_parts& h,
                                        const std::vector<int>& dropped, form_expressions& f) {
    const auto& s = symbols();
    const auto& q_names = f.angles.names;
    for (int i = 0; i < 3; ++i)
        if (!contains(dropped, i))
            f.state.push_back({q_names[i], s.q[i], "Euler angle (z-x-z), rad"});
    for (int i = 0; i < 3; ++i)
        if (!contains(dropped, i))
            f.state.push_back({"p_" + q_names[i], s.p[i], "its conjugate momentum"});
    std::vector<ex> structured;
    for (int i = 0; i < 3; ++i)
        if (!contains(dropped, i)) {
            f.rates.push_back(d.hamilton_qdot[i]);
            structured.push_back(h.qdot[i]);
            f.rate_names.push_back(q_names[i] + "_dot");
        }
    for (int i = 0; i < 3; ++i)
        if (!contains(dropped, i)) {
            f.rates.push_back(d.hamilton_pdot[i]);
            structured.push_back(h.pdot[i]);
            f.rate_names.push_back("p_" + q_names[i] + "_dot");
        }
    return structured;
}

// The conserved momenta of the ignored coordinates as parameters, and the note that says so.
void ignored_momenta(const std::vector<int>& dropped, form_expressions& f) {
    const auto& s = symbols();
    const auto& q_names = f.angles.names;
    std::string gone;
    for (int i : dropped) {
        gone += (gone.empty() ? "" : ", ") + q_names[i];
        f.parameters.push_back({"p_" + q_names[i], s.p[i], 0.0,
                                "conserved momentum of the ignored coordinate " + q_names[i],
                                false});
    }
    f.notes.push_back(
        "Routh reduction of the Hamiltonian form: the cyclic coordinates (" + gone +
        ") are ignored, their conserved momenta are parameters, their rates the output "
        "ignored_rates (integrate them to recover the angles).");
}

// Why an output that mentions the ignored coordinate q is unavailable.
std::string depends_on_ignored(const std::string& q) {
    return "it depends on the ignored coordinate " + q + "; use --form hamiltonian";
}

// An output, or the reason it is unavailable: it mentions an ignored angle.
void offer(form_expressions& f, const std::vector<int>& dropped, const std::string& name,
           std::vector<ex> values, std::vector<std::string> names) {
    const std::string q = mentioned_ignored(values, dropped, f.angles);
    if (q.empty())
        add_output(f, name, std::move(values), std::move(names));
    else
        f.unavailable[name] = depends_on_ignored(q);
}

// The outputs the reduced state determines. Three need no test: the ignored rates are
// d.hamilton_qdot of the ignored coordinates, which mention no ignored angle (ignored_coordinates
// chose them so), and the momenta are the symbols p: both are always available; the rotation A
// (5.25) always mentions every angle (A_11 = cos psi cos phi - cos theta sin phi sin psi), so it
// is never available. Energy, omega and M(q) depend on the model.
void reduced_outputs(const derivation& d, const hamilton_parts& h, const std::vector<int>& dropped,
                     form_expressions& f) {
    const auto& s = symbols();
    std::vector<ex> rates;
    std::vector<std::string> names;
    for (int i : dropped) {
        rates.push_back(d.hamilton_qdot[i]);
        names.push_back(f.angles.names[i] + "_dot");
    }
    add_output(f, "ignored_rates", rates, names);
    vec Iw = h.l; // I omega = l - h (a gyrostat's wheels)
    for (int i = 0; i < 3; ++i)
        Iw[i] = h.l[i] - d.wheels.h[i];
    const ex energy =
        d.wheels.any ? kinetic_of(d, h.w, Iw) + d.potential : dot(h.w, h.l) / 2 + d.potential;
    // H is the energy unless a wheel's rate is driven (then L depends on t)
    offer(f, dropped, "energy", {d.wheels.driven ? energy : d.hamiltonian}, {"energy"});
    if (f.outputs.count("energy") && mentioned_ignored({energy}, dropped, f.angles).empty())
        f.outputs["energy"].alternatives.push_back({energy});
    add_output(f, "momenta", {s.p[0], s.p[1], s.p[2]}, momentum_names(f.angles));
    offer(f, dropped, "omega", {h.w[0], h.w[1], h.w[2]}, {"omega1", "omega2", "omega3"});
    offer(f, dropped, "mass_matrix", flat(d.mass_matrix), matrix_names("M"));
    f.unavailable["rotation"] = depends_on_ignored(f.angles.names[dropped.front()]);
}

} // namespace

void build_reduced(const model_spec& spec, const derivation& d, form_expressions& f) {
    const hamilton_parts h = hamilton(d);
    const std::vector<int> dropped = ignored_coordinates(spec, d);
    const std::vector<ex> structured = reduced_state_and_rates(d, h, dropped, f);
    ignored_momenta(dropped, f);
    if (mentioned_ignored(structured, dropped, f.angles).empty())
        f.alternative_rates.push_back(structured);
    reduced_outputs(d, h, dropped, f);
}

} // namespace rotgen::form_detail
