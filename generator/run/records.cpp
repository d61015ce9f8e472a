// rotgen — run/: L1..L3, Lx..Lz, T and V from a form's outputs (records.hpp).
#include "run/records.hpp"

#include "derive/wheels.hpp"

#include <array>

namespace rotgen {

namespace {

using GiNaC::ex;

// The values of one of the form's outputs, if it has it.
const std::vector<ex>* output(const form_expressions& f, const std::string& name) {
    const auto it = f.outputs.find(name);
    return it == f.outputs.end() ? nullptr : &it->second.values;
}

// Whether e is an expression in the form's state, parameters and time only (the reduced form's
// state lacks its ignored angles).
bool in_form_terms(const form_expressions& f, const ex& e) {
    GiNaC::exset allowed{f.time};
    for (const auto& v : f.state)
        allowed.insert(v.symbol);
    for (const auto& p : f.parameters)
        allowed.insert(p.symbol);
    for (GiNaC::const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (GiNaC::is_a<GiNaC::symbol>(*it) && !allowed.count(*it)) return false;
    return true;
}

// L = I omega (body axes), when the form gives omega.
std::optional<std::array<ex, 3>> body_momentum(const model_spec& spec, const form_expressions& f) {
    const std::vector<ex>* w = output(f, "omega");
    if (!w) return std::nullopt;
    if (!spec.wheels.empty()) return gyrostat_momentum(spec, *w);
    std::array<ex, 3> l;
    for (std::size_t i = 0; i < 3; ++i) {
        l[i] = 0;
        for (std::size_t j = 0; j < 3; ++j)
            l[i] += spec.inertia[i][j] * (*w)[j];
    }
    return l;
}

// T = 1/2 omega . I omega (5.38), or energy - V where the form has no omega.
std::optional<ex> kinetic(const model_spec& spec, const form_expressions& f) {
    const std::vector<ex>* w = output(f, "omega");
    if (w && !spec.wheels.empty()) return gyrostat_kinetic(spec, *w);
    if (const auto l = body_momentum(spec, f))
        return ((*w)[0] * (*l)[0] + (*w)[1] * (*l)[1] + (*w)[2] * (*l)[2]) / 2;
    const std::vector<ex>* e = output(f, "energy");
    if (e && f.form != form_kind::body && in_form_terms(f, spec.potential))
        return (*e)[0] - spec.potential;
    return std::nullopt;
}

// V: the model's potential in the Euler-angle forms; energy - T in the body form, whose energy
// holds V in the quaternion (the gravity shorthand) or through the chart.
std::optional<ex> potential(const model_spec& spec, const form_expressions& f) {
    if (f.form != form_kind::body)
        return in_form_terms(f, spec.potential) ? std::optional<ex>(spec.potential) : std::nullopt;
    const std::vector<ex>* e = output(f, "energy");
    const auto t = kinetic(spec, f);
    return e && t ? std::optional<ex>((*e)[0] - *t) : std::nullopt;
}

} // namespace

std::optional<ex> derived_record(const model_spec& spec, const form_expressions& f,
                                 const std::string& name) {
    if (name == "T") return kinetic(spec, f);
    if (const std::vector<ex>* w = output(f, "omega"); w && !spec.wheels.empty())
        if (auto r = wheel_record(spec, *w, name)) return r;
    if (name == "V") return potential(spec, f);
    const auto l = body_momentum(spec, f);
    if (!l) return std::nullopt;
    for (std::size_t i = 0; i < 3; ++i)
        if (name == "L" + std::to_string(i + 1)) return (*l)[i];
    const std::vector<ex>* A = output(f, "rotation"); // row-major, body <- space
    for (std::size_t j = 0; j < 3 && A; ++j)
        if (name == std::string("L") + "xyz"[j]) { // (A^T L)_j = sum_i A_ij L_i
            ex v = 0;
            for (std::size_t i = 0; i < 3; ++i)
                v += (*A)[3 * i + j] * (*l)[i];
            return v;
        }
    return std::nullopt;
}

} // namespace rotgen
