// rotgen — derive/: the linear rotor's Lagrangian and Hamiltonian (rotor.hpp).
#include "derive/rotor.hpp"

#include "derive/derive.hpp"
#include "expr/symbols.hpp"

namespace rotgen {

using GiNaC::ex;

const std::array<GiNaC::realsymbol, 8>& rotor_chart2_symbols() {
    static const std::array<GiNaC::realsymbol, 8> s{
        GiNaC::realsymbol("phi2", "\\phi_2"),
        GiNaC::realsymbol("theta2", "\\theta_2"),
        GiNaC::realsymbol("phi2_dot", "\\dot{\\phi}_2"),
        GiNaC::realsymbol("theta2_dot", "\\dot{\\theta}_2"),
        GiNaC::realsymbol("phi2_ddot", "\\ddot{\\phi}_2"),
        GiNaC::realsymbol("theta2_ddot", "\\ddot{\\theta}_2"),
        GiNaC::realsymbol("p_phi2", "p_{\\phi_2}"),
        GiNaC::realsymbol("p_theta2", "p_{\\theta_2}")};
    return s;
}

std::optional<ex> rotor_potential_in_chart2(const model_spec& spec) {
    const auto& s = symbols();
    const auto& c2 = rotor_chart2_symbols();
    // V(cos theta) only: with sin(theta)^2 -> 1 - c^2 and cos(theta) -> c, no angle is left.
    const GiNaC::realsymbol c("rg_cos_theta");
    const ex in_c = spec.rotor_potential.expand()
                        .subs(GiNaC::pow(GiNaC::sin(s.q[1]), 2) == 1 - GiNaC::pow(c, 2),
                              GiNaC::subs_options::algebraic)
                        .subs(GiNaC::cos(s.q[1]) == c);
    if (in_c.has(s.q[0]) || in_c.has(s.q[1]) || in_c.has(s.q[2])) return std::nullopt;
    // n_z = -sin(theta2) cos(phi2) in chart 2
    return in_c.subs(c == -GiNaC::sin(c2[1]) * GiNaC::cos(c2[0])).expand();
}

namespace {

ex simplify(const ex& e, int chart) {
    return chart == 1 ? canonical(e) : e.expand();
}

void set_symbols(rotor_derivation& d) {
    const auto& s = symbols();
    const auto& c2 = rotor_chart2_symbols();
    for (std::size_t i = 0; i < 2; ++i) {
        d.q[i] = d.chart == 1 ? ex(s.q[i]) : ex(c2[i]);
        d.qd[i] = d.chart == 1 ? ex(s.qd[i]) : ex(c2[2 + i]);
        d.qdd[i] = d.chart == 1 ? ex(s.qdd[i]) : ex(c2[4 + i]);
        d.p[i] = d.chart == 1 ? ex(s.p[i]) : ex(c2[6 + i]);
    }
}

ex by(const ex& e, const ex& x) {
    return e.diff(GiNaC::ex_to<GiNaC::symbol>(x));
}

// H = p_theta^2 / (2 I) + p_phi^2 / (2 I sin^2 theta) + V (M diagonal), Hamilton's equations.
void hamiltonian(rotor_derivation& d) {
    const ex st = GiNaC::sin(d.q[1]);
    d.hamiltonian = simplify(GiNaC::pow(d.p[1], 2) / (2 * d.moment) +
                                 GiNaC::pow(d.p[0], 2) / (2 * d.moment * st * st) + d.potential,
                             d.chart);
    for (std::size_t i = 0; i < 2; ++i) {
        d.hamilton_qdot[i] = simplify(by(d.hamiltonian, d.p[i]), d.chart);
        d.hamilton_pdot[i] = simplify(-by(d.hamiltonian, d.q[i]), d.chart);
    }
}

} // namespace

rotor_derivation derive_rotor(const model_spec& spec, int chart) {
    rotor_derivation d;
    d.chart = chart;
    set_symbols(d);
    d.moment = spec.rotor_moment;
    const ex st = GiNaC::sin(d.q[1]);
    // T = 1/2 I (theta_dot^2 + sin^2 theta phi_dot^2)
    d.kinetic = simplify(d.moment * (d.qd[1] * d.qd[1] + st * st * d.qd[0] * d.qd[0]) / 2, chart);
    d.potential = chart == 1 ? canonical(spec.rotor_potential) : *rotor_potential_in_chart2(spec);
    d.lagrangian = simplify(d.kinetic - d.potential, chart);
    d.energy = simplify(d.kinetic + d.potential, chart);
    for (std::size_t i = 0; i < 2; ++i)
        d.momenta[i] = simplify(by(d.lagrangian, d.qd[i]), chart);
    for (std::size_t i = 0; i < 2; ++i)
        for (std::size_t j = 0; j < 2; ++j)
            d.mass_matrix[i][j] = simplify(by(d.momenta[i], d.qd[j]), chart);
    for (std::size_t i = 0; i < 2; ++i) {
        ex f = by(d.lagrangian, d.q[i]);
        for (std::size_t j = 0; j < 2; ++j)
            f -= by(d.momenta[i], d.q[j]) * d.qd[j];
        d.forcing[i] = simplify(f, chart);
        ex el = -d.forcing[i];
        for (std::size_t j = 0; j < 2; ++j)
            el += d.mass_matrix[i][j] * d.qdd[j];
        d.euler_lagrange[i] = simplify(el, chart);
    }
    hamiltonian(d);
    for (int i = 0; i < 2; ++i)
        if (simplify(by(d.lagrangian, d.q[static_cast<std::size_t>(i)]), chart).is_zero())
            d.cyclic.push_back(i);
    return d;
}

} // namespace rotgen
