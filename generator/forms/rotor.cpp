// rotgen — forms/: the linear rotor's form (Example 5.4; derive/rotor.hpp), y = (phi, theta,
// phi_dot, theta_dot), M q_ddot = f with M = diag(I sin^2 theta, I):
//   phi_ddot   = f_phi / (I sin^2 theta) = -V_phi / (I sin^2 theta) - 2 cot(theta) theta_dot
//   phi_dot theta_ddot = f_theta / I             = sin(theta) cos(theta) phi_dot^2 - V_theta / I.
// Chart 2 (form rotor_x, y = (phi2, theta2, phi2_dot, theta2_dot)) is the same in the angles of
// the permuted direction (n_y, n_z, n_x); a run near chart 1's pole continues in it.
//
// Outputs: energy, momenta (p_phi, p_theta), mass_matrix (2 x 2). The recorded quantities the run
// needs go in the output group `rotor_records`, which the emitter does not write (it writes only
// output_names()): T, V and the angular momentum in space axes L = I n x n_dot, n the line's
// direction (5.25, third row of A); in chart 2 also chart 1's angles, rates and momenta,
//   theta = atan2(sqrt(n_x^2 + n_y^2), n_z),  phi = atan2(n_x, -n_y),
//   phi_dot = (n_x n_y' - n_y n_x') / (n_x^2 + n_y^2),  theta_dot = -n_z' / sqrt(n_x^2 + n_y^2),
//   p_phi = I (n_x n_y' - n_y n_x') = L_z,  p_theta = I theta_dot.
#include "derive/rotor.hpp"
#include "forms/form_algebra.hpp"

namespace rotgen::form_detail {

using GiNaC::ex;

namespace {

// The line's direction in space from the chart's angles (for chart 2 the permutation undone).
vec direction(const rotor_derivation& d) {
    const ex st = GiNaC::sin(d.q[1]), ct = GiNaC::cos(d.q[1]);
    const vec m{st * GiNaC::sin(d.q[0]), -st * GiNaC::cos(d.q[0]), ct};
    return d.chart == 1 ? m : vec{m[2], m[0], m[1]};
}

vec rate_of(const rotor_derivation& d, const vec& n) {
    vec r;
    for (std::size_t i = 0; i < 3; ++i)
        r[i] = (n[i].diff(GiNaC::ex_to<GiNaC::symbol>(d.q[0])) * d.qd[0] +
                n[i].diff(GiNaC::ex_to<GiNaC::symbol>(d.q[1])) * d.qd[1])
                   .expand();
    return r;
}

void records(const rotor_derivation& d, form_expressions& f) {
    const vec n = direction(d), nd = rate_of(d, n);
    const vec l = cross(n, nd);
    std::vector<ex> values{d.kinetic, d.potential};
    std::vector<std::string> names{"T", "V"};
    for (std::size_t i = 0; i < 3; ++i) {
        values.push_back(d.moment * l[i]);
        names.push_back(std::string("L") + "xyz"[i]);
    }
    if (d.chart == 2) {
        const ex rho2 = n[0] * n[0] + n[1] * n[1], rho = GiNaC::sqrt(rho2);
        const ex theta_dot = -nd[2] / rho;
        values.insert(values.end(),
                      {GiNaC::atan2(n[0], -n[1]), GiNaC::atan2(rho, n[2]), l[2] / rho2, theta_dot,
                       d.moment * l[2], d.moment * theta_dot});
        names.insert(names.end(), {"phi", "theta", "phi_dot", "theta_dot", "p_phi", "p_theta"});
    }
    add_output(f, "rotor_records", values, names);
}

} // namespace

void build_rotor(const model_spec& spec, form_expressions& f, int chart) {
    const rotor_derivation d = derive_rotor(spec, chart);
    const std::string suffix = chart == 1 ? "" : "2";
    const std::array<std::string, 2> q{"phi" + suffix, "theta" + suffix};
    for (std::size_t i = 0; i < 2; ++i)
        f.state.push_back({q[i], d.q[i], "angle of the rotor's line, rad"});
    for (std::size_t i = 0; i < 2; ++i)
        f.state.push_back({q[i] + "_dot", d.qd[i], "its rate, rad/time"});
    for (std::size_t i = 0; i < 2; ++i) {
        f.rates.push_back(d.qd[i]);
        f.rate_names.push_back(q[i] + "_dot");
    }
    // M is diagonal: q_ddot_i = f_i / M_ii
    for (std::size_t i = 0; i < 2; ++i) {
        f.rates.push_back(d.forcing[i] / d.mass_matrix[i][i]);
        f.rate_names.push_back(q[i] + "_ddot");
    }
    f.notes.push_back(
        "Linear rotor (Example 5.4): the line is body axis 3 of z-x-z angles, its direction in "
        "space n = (sin theta sin phi, -sin theta cos phi, cos theta) (third row of A, 5.25); "
        "T = 1/2 I (theta_dot^2 + sin^2 theta phi_dot^2), M = diag(I sin^2 theta, I), "
        "q_ddot_i = f_i / M_ii.");
    if (chart == 2)
        f.notes.push_back("Chart 2: phi2, theta2 are the angles of (n_y, n_z, n_x); its pole is "
                          "the x axis.");
    add_output(f, "energy", {d.energy}, {"energy"});
    add_output(f, "momenta", {d.momenta[0], d.momenta[1]}, {"p_" + q[0], "p_" + q[1]});
    add_output(f, "mass_matrix",
               {d.mass_matrix[0][0], d.mass_matrix[0][1], d.mass_matrix[1][0], d.mass_matrix[1][1]},
               {"M11", "M12", "M21", "M22"});
    const std::string why = "a linear rotor has no body axes beyond its line";
    for (const char* name : {"omega", "rotation", "ignored_rates"})
        f.unavailable[name] = why;
    records(d, f);
}

} // namespace rotgen::form_detail
