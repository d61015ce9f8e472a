// rotgen — forms/: vector algebra, the inline L D L^T, output helpers and the Hamiltonian pieces
// shared by the forms (form_algebra.hpp).
#include "forms/form_algebra.hpp"

#include "expr/symbols.hpp"

namespace rotgen::form_detail {

using GiNaC::ex;

vec mat_vec(const matrix3& m, const vec& v) {
    vec r;
    for (int i = 0; i < 3; ++i) {
        r[i] = 0;
        for (int j = 0; j < 3; ++j)
            r[i] += m[i][j] * v[j];
    }
    return r;
}

vec mat_t_vec(const matrix3& m, const vec& v) {
    vec r;
    for (int i = 0; i < 3; ++i) {
        r[i] = 0;
        for (int j = 0; j < 3; ++j)
            r[i] += m[j][i] * v[j];
    }
    return r;
}

vec cross(const vec& a, const vec& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

ex dot(const vec& a, const vec& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

ldlt ldlt_factor(const matrix3& M) {
    ldlt F;
    F.d0 = M[0][0];
    F.l10 = M[1][0] / F.d0;
    F.l20 = M[2][0] / F.d0;
    F.d1 = M[1][1] - F.l10 * M[1][0];
    const ex u = M[2][1] - F.l20 * M[1][0];
    F.l21 = u / F.d1;
    F.d2 = M[2][2] - F.l20 * M[2][0] - F.l21 * u;
    return F;
}

vec ldlt_solve(const ldlt& F, const vec& b) {
    const ex z0 = b[0];
    const ex z1 = b[1] - F.l10 * z0;
    const ex z2 = b[2] - F.l20 * z0 - F.l21 * z1;
    const ex x2 = z2 / F.d2;
    const ex x1 = z1 / F.d1 - F.l21 * x2;
    const ex x0 = z0 / F.d0 - F.l10 * x1 - F.l20 * x2;
    return {x0, x1, x2};
}

std::vector<ex> flat(const matrix3& m) {
    std::vector<ex> v;
    for (const auto& row : m)
        for (const ex& e : row)
            v.push_back(e);
    return v;
}

std::vector<std::string> matrix_names(const std::string& m) {
    std::vector<std::string> n;
    for (int i = 1; i <= 3; ++i)
        for (int j = 1; j <= 3; ++j)
            n.push_back(m + std::to_string(i) + std::to_string(j));
    return n;
}

void add_output(form_expressions& f, const std::string& name, std::vector<ex> values,
                std::vector<std::string> names) {
    f.outputs[name] = form_output{std::move(values), std::move(names), {}};
}

ex kinetic_of(const derivation& d, const vec& w, const vec& Iw) {
    if (!d.wheels.any) return dot(w, Iw) / 2;
    const vec hd{d.wheels.h_driven[0], d.wheels.h_driven[1], d.wheels.h_driven[2]};
    return dot(w, Iw) / 2 + dot(hd, w) + d.wheels.kinetic;
}

vec momentum_of(const derivation& d, const vec& Iw) {
    if (!d.wheels.any) return Iw;
    return {Iw[0] + d.wheels.h[0], Iw[1] + d.wheels.h[1], Iw[2] + d.wheels.h[2]};
}

hamilton_parts hamilton(const derivation& d) {
    const auto& s = symbols();
    hamilton_parts h;
    h.l = d.body_momentum; // l = J^{-T} p
    vec lb = h.l;          // l - h: the body's own momentum I omega (a gyrostat's wheels)
    if (d.wheels.any)
        for (int i = 0; i < 3; ++i)
            lb[i] = h.l[i] - d.wheels.h[i];
    h.w = mat_vec(d.inverse_inertia, lb);            // omega = I^{-1} (l - h)
    h.qdot = mat_vec(d.inverse_omega_jacobian, h.w); // q_dot = J^{-1} omega = dH/dp
    GiNaC::exmap rates;
    for (int i = 0; i < 3; ++i)
        rates[s.qd[i]] = h.qdot[i];
    for (int i = 0; i < 3; ++i) {
        // dH/dq_i = omega . dl/dq_i + dV/dq_i  (H = 1/2 l . I^{-1} l + V)
        vec dl;
        for (int k = 0; k < 3; ++k)
            dl[k] = h.l[k].diff(s.q[i]);
        h.pdot[i] = -dot(h.w, dl) - d.potential.diff(s.q[i]) + d.generalized_force[i].subs(rates);
    }
    return h;
}

} // namespace rotgen::form_detail
