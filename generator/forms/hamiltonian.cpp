// rotgen — forms/: the Hamiltonian form, y = (phi, theta, psi, p_phi, p_theta, p_psi):
// l = J^{-T} p, omega = I^{-1} l, q_dot = J^{-1} omega = dH/dp, p_dot = -dH/dq + Q
// (H = 1/2 l . I^{-1} l + V; the pieces are form_algebra.cpp's hamilton()).
#include "forms/form_algebra.hpp"

#include "expr/angles.hpp"
#include "expr/symbols.hpp"

namespace rotgen::form_detail {

void build_hamiltonian(const model_spec& spec, const derivation& d, form_expressions& f) {
    const auto& s = symbols();
    const auto& q_names = f.angles.names;
    for (int i = 0; i < 3; ++i)
        f.state.push_back({q_names[i], s.q[i], "Euler angle (z-x-z), rad"});
    for (int i = 0; i < 3; ++i)
        f.state.push_back({"p_" + q_names[i], s.p[i], "its conjugate momentum"});
    const hamilton_parts h = hamilton(d);
    for (int i = 0; i < 3; ++i) {
        f.rates.push_back(h.qdot[i]);
        f.rate_names.push_back(q_names[i] + "_dot");
    }
    for (int i = 0; i < 3; ++i) {
        f.rates.push_back(h.pdot[i]);
        f.rate_names.push_back("p_" + q_names[i] + "_dot");
    }
    f.alternative_rates.push_back({d.hamilton_qdot[0], d.hamilton_qdot[1], d.hamilton_qdot[2],
                                   d.hamilton_pdot[0], d.hamilton_pdot[1], d.hamilton_pdot[2]});
    GiNaC::exmap in_state; // a wheel's torque: omega = I^{-1} (l - h), q_dot = J^{-1} omega
    for (int i = 0; i < 3; ++i) {
        in_state[s.omega[i]] = h.w[i];
        in_state[s.qd[i]] = h.qdot[i];
    }
    add_wheel_states(spec, f, [&](const GiNaC::ex& e) { return e.subs(in_state); });
    f.notes.push_back(
        "l = J^{-T} p (body angular momentum), omega = I^{-1} l, q_dot = J^{-1} omega = dH/dp, "
        "p_dot = -dH/dq + Q; " +
        f.angles.singular_clause() + ".");
    if (d.wheels.any) { // h.l - h = I omega
        const vec Iw{h.l[0] - d.wheels.h[0], h.l[1] - d.wheels.h[1], h.l[2] - d.wheels.h[2]};
        add_output(f, "energy", {kinetic_of(d, h.w, Iw) + d.potential}, {"energy"});
    } else {
        add_output(f, "energy", {dot(h.w, h.l) / 2 + d.potential}, {"energy"});
    }
    if (!d.wheels.driven) f.outputs["energy"].alternatives.push_back({d.hamiltonian});
    add_output(f, "momenta", {s.p[0], s.p[1], s.p[2]}, momentum_names(f.angles));
    add_output(f, "omega", {h.w[0], h.w[1], h.w[2]}, {"omega1", "omega2", "omega3"});
}

} // namespace rotgen::form_detail
