#include "forms/forms.hpp"

#include "support/error.hpp"
#include "expr/symbols.hpp"

#include <algorithm>

namespace rotgen {

using GiNaC::ex;

const char* to_string(lagrangian_strategy s) {
    return s == lagrangian_strategy::solve ? "solve" : "explicit";
}

const std::array<GiNaC::realsymbol, 4>& quaternion_symbols() {
    static const std::array<GiNaC::realsymbol, 4> q{
        GiNaC::realsymbol("qw", "q_{w}"), GiNaC::realsymbol("qx", "q_{x}"),
        GiNaC::realsymbol("qy", "q_{y}"), GiNaC::realsymbol("qz", "q_{z}")};
    return q;
}

const std::vector<std::string>& output_names() {
    static const std::vector<std::string> names{"rhs",      "jacobian",     "energy",
                                                "momenta",  "mass_matrix",  "omega",
                                                "rotation", "ignored_rates"};
    return names;
}

std::array<ex, 9> rotation_matrix() {
    // (5.25): A = Az(psi) Ax(theta) Az(phi), Az(a) = [[c, s, 0], [-s, c, 0], [0, 0, 1]],
    // Ax(a) = [[1, 0, 0], [0, c, s], [0, -s, c]] (5.8, 5.9).
    const auto& s = symbols();
    const auto az = [](const ex& a) {
        return std::array<ex, 9>{
            GiNaC::cos(a), GiNaC::sin(a), 0, -GiNaC::sin(a), GiNaC::cos(a), 0, 0, 0, 1};
    };
    const auto ax = [](const ex& a) {
        return std::array<ex, 9>{
            1, 0, 0, 0, GiNaC::cos(a), GiNaC::sin(a), 0, -GiNaC::sin(a), GiNaC::cos(a)};
    };
    const auto times = [](const std::array<ex, 9>& a, const std::array<ex, 9>& b) {
        std::array<ex, 9> c;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                ex v = 0;
                for (int k = 0; k < 3; ++k)
                    v += a[3 * i + k] * b[3 * k + j];
                c[3 * i + j] = v.expand();
            }
        return c;
    };
    return times(az(s.q[2]), times(ax(s.q[1]), az(s.q[0])));
}

namespace {

using vec = std::array<ex, 3>;

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

// M = L D L^T for a symmetric 3x3 M (lower triangle read), L unit lower triangular.
struct ldlt {
    ex l10, l20, l21, d0, d1, d2;
};

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

// x with L D L^T x = b: forward substitution, diagonal, back substitution.
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

std::vector<form_parameter> model_parameters(const model_spec& spec) {
    std::vector<form_parameter> ps;
    for (const parameter& p : spec.parameters)
        ps.push_back({p.name, p.symbol, p.value, p.description, true});
    return ps;
}

// The gravity shorthand's potential, as spec.cpp builds it: M g (com . e), e = (sin theta sin psi,
// sin theta cos psi, cos theta) the third column of A.
ex gravity_potential(const model_spec& spec) {
    if (!spec.gravity) return 0;
    const auto& s = symbols();
    const vec e{GiNaC::sin(s.q[1]) * GiNaC::sin(s.q[2]), GiNaC::sin(s.q[1]) * GiNaC::cos(s.q[2]),
                GiNaC::cos(s.q[1])};
    ex h = 0;
    for (int i = 0; i < 3; ++i)
        h += spec.gravity->com[i] * e[i];
    return spec.gravity->mass * spec.gravity->g * h;
}

void add_output(form_expressions& f, const std::string& name, std::vector<ex> values,
                std::vector<std::string> names) {
    f.outputs[name] = form_output{std::move(values), std::move(names), {}};
}

const std::vector<std::string> q_names{"phi", "theta", "psi"};

// ---- the Euler-angle forms ----

void lagrangian(const model_spec& spec, const derivation& d, form_expressions& f) {
    const auto& s = symbols();
    for (int i = 0; i < 3; ++i)
        f.state.push_back({q_names[i], s.q[i], "Euler angle (z-x-z), rad"});
    for (int i = 0; i < 3; ++i)
        f.state.push_back({q_names[i] + "_dot", s.qd[i], "its rate, rad/time"});
    for (int i = 0; i < 3; ++i) {
        f.rates.push_back(s.qd[i]);
        f.rate_names.push_back(q_names[i] + "_dot");
    }
    if (f.strategy == lagrangian_strategy::explicit_inverse) {
        // q_ddot = M^{-1} f with M^{-1} = J^{-1} I^{-1} J^{-T}, applied right to left.
        const vec g = mat_t_vec(d.inverse_omega_jacobian, d.forcing);
        const vec h = mat_vec(d.inverse_inertia, g);
        const vec qdd = mat_vec(d.inverse_omega_jacobian, h);
        for (int i = 0; i < 3; ++i)
            f.rates.push_back(qdd[i]);
        // Alternatively M^{-1} itself in canonical form (identities such as sin^2 + cos^2 of psi
        // cancel there), times f.
        matrix3 minv;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                ex e = 0;
                for (int k = 0; k < 3; ++k)
                    for (int l = 0; l < 3; ++l)
                        e += d.inverse_omega_jacobian[i][k] * d.inverse_inertia[k][l] *
                             d.inverse_omega_jacobian[j][l];
                minv[i][j] = canonical(e);
            }
        const vec qdd2 = mat_vec(minv, d.forcing);
        f.alternative_rates.push_back({s.qd[0], s.qd[1], s.qd[2], qdd2[0], qdd2[1], qdd2[2]});
        // Or by Euler's equations: omega_dot = I^{-1} (tau - omega x I omega), tau = J^{-T} Q_total
        // (Q_total = -dV/dq + Q, in canonical form: for gravity the 1/sin(theta) cancels), and
        // q_ddot = J^{-1} (omega_dot - J_dot q_dot), J_dot q_dot = sum_j d omega/d q_j q_dot_j.
        vec q_total;
        for (int i = 0; i < 3; ++i)
            q_total[i] = -d.potential.diff(s.q[i]) + d.generalized_force[i];
        vec tau = mat_t_vec(d.inverse_omega_jacobian, q_total);
        for (auto& t : tau)
            t = canonical(t);
        const vec Iw = mat_vec(spec.inertia, d.omega);
        const vec gyro = cross(d.omega, Iw);
        vec b;
        for (int i = 0; i < 3; ++i)
            b[i] = tau[i] - gyro[i];
        const vec wd = mat_vec(d.inverse_inertia, b);
        vec a;
        for (int i = 0; i < 3; ++i) {
            ex jdot = 0;
            for (int j = 0; j < 3; ++j)
                jdot += d.omega[i].diff(s.q[j]) * s.qd[j];
            a[i] = wd[i] - canonical(jdot);
        }
        const vec qdd3 = mat_vec(d.inverse_omega_jacobian, a);
        f.alternative_rates.push_back({s.qd[0], s.qd[1], s.qd[2], qdd3[0], qdd3[1], qdd3[2]});
        f.notes.push_back(
            "q_ddot = J^{-1} I^{-1} J^{-T} f (M^{-1} = J^{-1} I^{-1} J^{-T}, M = J^T I J, "
            "J = d omega/d q_dot of (5.30)); singular at theta = 0, pi through 1/sin(theta).");
    } else {
        // M q_ddot = f by LDL^T, written out: the zeros of M drop out as the code is built.
        f.mass = d.mass_matrix;
        f.forcing = d.forcing;
        const vec qdd = ldlt_solve(ldlt_factor(f.mass), d.forcing);
        for (int i = 0; i < 3; ++i)
            f.rates.push_back(qdd[i]);
        f.notes.push_back(
            "M(q) q_ddot = f(t, q, q_dot) solved by an inline LDL^T (no pivoting; M = J^T I J "
            "is positive definite for 0 < theta < pi, singular at theta = 0, pi).");
    }
    for (int i = 0; i < 3; ++i)
        f.rate_names.push_back(q_names[i] + "_ddot");

    // omega = J q_dot (5.30); T = 1/2 omega . I omega (5.38); p = J^T I omega.
    const vec w = d.omega;
    const vec Iw = mat_vec(spec.inertia, w);
    add_output(f, "energy", {dot(w, Iw) / 2 + d.potential}, {"energy"});
    f.outputs["energy"].alternatives.push_back({d.energy});
    const vec p = mat_t_vec(d.omega_jacobian, Iw);
    add_output(f, "momenta", {p[0], p[1], p[2]}, {"p_phi", "p_theta", "p_psi"});
    f.outputs["momenta"].alternatives.push_back({d.momenta[0], d.momenta[1], d.momenta[2]});
    add_output(f, "omega", {w[0], w[1], w[2]}, {"omega1", "omega2", "omega3"});
}

struct hamilton_parts {
    vec l, w, qdot, pdot;
};

hamilton_parts hamilton(const model_spec& spec, const derivation& d) {
    (void)spec;
    const auto& s = symbols();
    hamilton_parts h;
    h.l = d.body_momentum;                           // l = J^{-T} p
    h.w = mat_vec(d.inverse_inertia, h.l);           // omega = I^{-1} l
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

void hamiltonian(const model_spec& spec, const derivation& d, form_expressions& f) {
    const auto& s = symbols();
    for (int i = 0; i < 3; ++i)
        f.state.push_back({q_names[i], s.q[i], "Euler angle (z-x-z), rad"});
    for (int i = 0; i < 3; ++i)
        f.state.push_back({"p_" + q_names[i], s.p[i], "its conjugate momentum"});
    const hamilton_parts h = hamilton(spec, d);
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
    f.notes.push_back(
        "l = J^{-T} p (body angular momentum), omega = I^{-1} l, q_dot = J^{-1} omega = dH/dp, "
        "p_dot = -dH/dq + Q; singular at theta = 0, pi through 1/sin(theta).");
    add_output(f, "energy", {dot(h.w, h.l) / 2 + d.potential}, {"energy"});
    f.outputs["energy"].alternatives.push_back({d.hamiltonian});
    add_output(f, "momenta", {s.p[0], s.p[1], s.p[2]}, {"p_phi", "p_theta", "p_psi"});
    add_output(f, "omega", {h.w[0], h.w[1], h.w[2]}, {"omega1", "omega2", "omega3"});
}

void reduced(const model_spec& spec, const derivation& d, form_expressions& f) {
    const auto& s = symbols();
    const hamilton_parts h = hamilton(spec, d);
    // Cyclic coordinates (absent from L and Q) that the remaining equations do not mention, in the
    // canonical form (where identities such as sin^2 psi + cos^2 psi = 1 have cancelled).
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
    const auto is_dropped = [&](int i) {
        return std::find(dropped.begin(), dropped.end(), i) != dropped.end();
    };
    std::string kept, gone;
    for (int i = 0; i < 3; ++i)
        if (!is_dropped(i)) {
            f.state.push_back({q_names[i], s.q[i], "Euler angle (z-x-z), rad"});
            kept += (kept.empty() ? "" : ", ") + q_names[i];
        } else {
            gone += (gone.empty() ? "" : ", ") + q_names[i];
        }
    for (int i = 0; i < 3; ++i)
        if (!is_dropped(i))
            f.state.push_back({"p_" + q_names[i], s.p[i], "its conjugate momentum"});
    // The canonical equations, and the composed ones if they do not mention an ignored angle
    // (they may, where only an identity removes it).
    std::vector<ex> structured;
    for (int i = 0; i < 3; ++i)
        if (!is_dropped(i)) {
            f.rates.push_back(d.hamilton_qdot[i]);
            structured.push_back(h.qdot[i]);
            f.rate_names.push_back(q_names[i] + "_dot");
        }
    for (int i = 0; i < 3; ++i)
        if (!is_dropped(i)) {
            f.rates.push_back(d.hamilton_pdot[i]);
            structured.push_back(h.pdot[i]);
            f.rate_names.push_back("p_" + q_names[i] + "_dot");
        }
    for (int i : dropped)
        f.parameters.push_back({"p_" + q_names[i], s.p[i], 0.0,
                                "conserved momentum of the ignored coordinate " + q_names[i],
                                false});
    f.notes.push_back(
        "Routh reduction of the Hamiltonian form: the cyclic coordinates (" + gone +
        ") are ignored, their conserved momenta are parameters, their rates the output "
        "ignored_rates (integrate them to recover the angles).");

    std::vector<ex> rates;
    std::vector<std::string> names;
    for (int i : dropped) {
        rates.push_back(d.hamilton_qdot[i]);
        names.push_back(q_names[i] + "_dot");
    }
    const auto mentions_dropped = [&](const std::vector<ex>& v) {
        for (const ex& e : v)
            for (int i : dropped)
                if (e.has(s.q[i])) return q_names[i];
        return std::string();
    };
    const auto offer = [&](const std::string& name, std::vector<ex> values,
                           std::vector<std::string> n) {
        const std::string q = mentions_dropped(values);
        if (q.empty())
            add_output(f, name, std::move(values), std::move(n));
        else
            f.unavailable[name] =
                "it depends on the ignored coordinate " + q + "; use --form hamiltonian";
    };
    if (mentions_dropped(structured).empty()) f.alternative_rates.push_back(structured);
    offer("ignored_rates", rates, names);
    offer("energy", {d.hamiltonian}, {"energy"});
    if (f.outputs.count("energy") && mentions_dropped({dot(h.w, h.l) / 2 + d.potential}).empty())
        f.outputs["energy"].alternatives.push_back({dot(h.w, h.l) / 2 + d.potential});
    offer("momenta", {s.p[0], s.p[1], s.p[2]}, {"p_phi", "p_theta", "p_psi"});
    offer("omega", {h.w[0], h.w[1], h.w[2]}, {"omega1", "omega2", "omega3"});
    offer("mass_matrix", flat(d.mass_matrix), matrix_names("M"));
    const auto A = rotation_matrix();
    offer("rotation", std::vector<ex>(A.begin(), A.end()), matrix_names("A"));
    (void)kept;
}

// ---- the body form ----

void body(const model_spec& spec, const derivation& d, form_expressions& f, bool orientation) {
    const auto& s = symbols();
    const auto& Q = quaternion_symbols();
    const ex qw = Q[0], qx = Q[1], qy = Q[2], qz = Q[3];
    const vec w{s.omega[0], s.omega[1], s.omega[2]};

    // R(q) = A^T (body -> space), divided by |q|^2 so that it is a rotation for any q != 0.
    const ex n2 = qw * qw + qx * qx + qy * qy + qz * qz;
    const std::array<ex, 9> R{(qw * qw + qx * qx - qy * qy - qz * qz) / n2,
                              2 * (qx * qy - qw * qz) / n2,
                              2 * (qx * qz + qw * qy) / n2,
                              2 * (qx * qy + qw * qz) / n2,
                              (qw * qw - qx * qx + qy * qy - qz * qz) / n2,
                              2 * (qy * qz - qw * qx) / n2,
                              2 * (qx * qz - qw * qy) / n2,
                              2 * (qy * qz + qw * qx) / n2,
                              (qw * qw - qx * qx - qy * qy + qz * qz) / n2};
    // e, the space vertical in body axes: A's third column = R's third row.
    const vec e{R[6], R[7], R[8]};

    // The Euler-angle chart, for whatever is only known in angles: from R = Rz(phi) Rx(theta)
    // Rz(psi), R20 = sin(theta) sin(psi), R21 = sin(theta) cos(psi), R22 = cos(theta), R02 =
    // sin(phi) sin(theta), R12 = -cos(phi) sin(theta).
    const ex st = GiNaC::sqrt(R[6] * R[6] + R[7] * R[7]);
    GiNaC::exmap trig_value;
    std::array<GiNaC::realsymbol, 6> place{
        GiNaC::realsymbol("rg_sin_phi"),   GiNaC::realsymbol("rg_cos_phi"),
        GiNaC::realsymbol("rg_sin_theta"), GiNaC::realsymbol("rg_cos_theta"),
        GiNaC::realsymbol("rg_sin_psi"),   GiNaC::realsymbol("rg_cos_psi")};
    trig_value[place[0]] = R[2] / st;
    trig_value[place[1]] = -R[5] / st;
    trig_value[place[2]] = st;
    trig_value[place[3]] = R[8];
    trig_value[place[4]] = R[6] / st;
    trig_value[place[5]] = R[7] / st;
    GiNaC::exmap to_place, angle_value;
    for (int i = 0; i < 3; ++i) {
        to_place[GiNaC::sin(s.q[i])] = place[2 * i];
        to_place[GiNaC::cos(s.q[i])] = place[2 * i + 1];
    }
    angle_value[s.q[0]] = GiNaC::atan2(R[2], -R[5]);
    angle_value[s.q[1]] = GiNaC::atan2(st, R[8]);
    angle_value[s.q[2]] = GiNaC::atan2(R[6], R[7]);
    GiNaC::exmap rates; // q_dot = J^{-1} omega
    const vec qdot = mat_vec(d.inverse_omega_jacobian, w);
    for (int i = 0; i < 3; ++i)
        rates[s.qd[i]] = qdot[i];
    bool chart_used = false;
    const auto chart = [&](const ex& x) {
        ex y = x.subs(rates);
        if (y.is_equal(x) && !x.has(s.q[0]) && !x.has(s.q[1]) && !x.has(s.q[2])) return x;
        chart_used = true;
        y = y.subs(to_place).subs(angle_value).subs(trig_value);
        return y;
    };

    // The torque: gravity in closed form, the rest through the chart.
    vec tau{0, 0, 0};
    bool needs_orientation = false;
    if (spec.gravity) {
        const vec r{spec.gravity->com[0], spec.gravity->com[1], spec.gravity->com[2]};
        const ex Mg = spec.gravity->mass * spec.gravity->g;
        const vec c = cross(r, e);
        for (int i = 0; i < 3; ++i)
            tau[i] += -Mg * c[i]; // r_com x (-M g e)
        needs_orientation = true;
    }
    const ex v_rest = (spec.potential - gravity_potential(spec)).expand();
    ex v_body = 0;
    if (spec.gravity) {
        ex h = 0;
        for (int i = 0; i < 3; ++i)
            h += spec.gravity->com[i] * e[i];
        v_body = spec.gravity->mass * spec.gravity->g * h;
    }
    if (!v_rest.is_zero()) {
        // tau = -J^{-T} dV/dq
        vec dv;
        for (int i = 0; i < 3; ++i)
            dv[i] = v_rest.diff(s.q[i]);
        const vec t = mat_t_vec(d.inverse_omega_jacobian, dv);
        for (int i = 0; i < 3; ++i)
            tau[i] += chart(-t[i]);
        v_body += chart(v_rest);
        needs_orientation = true;
    }
    if (spec.has_damping) {
        // generalised force -c q_dot, as a torque J^{-T} Q
        vec q;
        for (int i = 0; i < 3; ++i)
            q[i] = -spec.damping[i] * s.qd[i];
        const vec t = mat_t_vec(d.inverse_omega_jacobian, q);
        bool zero = true;
        for (int i = 0; i < 3; ++i)
            zero = zero && t[i].expand().is_zero();
        if (!zero) {
            for (int i = 0; i < 3; ++i)
                tau[i] += chart(t[i]);
            needs_orientation = true;
        }
    }
    if (spec.has_torque)
        for (int i = 0; i < 3; ++i) {
            const ex t = chart(spec.torque[i]);
            if (!t.is_equal(spec.torque[i])) needs_orientation = true;
            tau[i] += t;
        }
    const bool quaternion = needs_orientation || orientation;

    if (quaternion)
        for (int i = 0; i < 4; ++i)
            f.state.push_back(
                {Q[i].get_name(), Q[i], "orientation quaternion (body -> space), any norm"});
    for (int i = 0; i < 3; ++i)
        f.state.push_back(
            {"omega" + std::to_string(i + 1), s.omega[i], "body angular velocity, rad/time"});

    if (quaternion) {
        // q_dot = 1/2 q (x) (0, omega)
        const std::array<ex, 4> qd{
            (-qx * w[0] - qy * w[1] - qz * w[2]) / 2, (qw * w[0] + qy * w[2] - qz * w[1]) / 2,
            (qw * w[1] + qz * w[0] - qx * w[2]) / 2, (qw * w[2] + qx * w[1] - qy * w[0]) / 2};
        for (int i = 0; i < 4; ++i) {
            f.rates.push_back(qd[i]);
            f.rate_names.push_back(Q[i].get_name() + "_dot");
        }
    }
    // I omega_dot = tau - omega x I omega
    const vec Iw = mat_vec(spec.inertia, w);
    const vec gyro = cross(w, Iw);
    vec rhs;
    for (int i = 0; i < 3; ++i)
        rhs[i] = tau[i] - gyro[i];
    const vec wd = mat_vec(d.inverse_inertia, rhs);
    for (int i = 0; i < 3; ++i) {
        f.rates.push_back(wd[i]);
        f.rate_names.push_back("omega" + std::to_string(i + 1) + "_dot");
    }

    f.notes.push_back(
        "I omega_dot = tau - omega x I omega (Euler's equations (5.87)-(5.89) for a full tensor "
        "with torque)" +
        std::string(quaternion ? "; q_dot = 1/2 q (x) (0, omega)." : "."));
    if (quaternion)
        f.notes.push_back(
            "q = (qw, qx, qy, qz) rotates body axes into space axes: R(q) = A^T with A of "
            "(5.25); from Euler angles q = qz(phi) (x) qx(theta) (x) qz(psi). Every use "
            "divides by |q|^2, so q need not stay normalised.");
    if (spec.gravity)
        f.notes.push_back(
            "gravity torque r_com x (-M g e), e = third row of R(q): no singularity.");
    f.uses_euler_chart = chart_used;
    if (chart_used)
        f.notes.push_back(
            "WARNING: part of the torque or potential is known only in Euler angles and is "
            "evaluated through the chart (angles from q): singular at theta = 0, pi.");

    add_output(f, "energy", {dot(w, Iw) / 2 + v_body}, {"energy"});
    add_output(f, "momenta", {Iw[0], Iw[1], Iw[2]}, {"l1", "l2", "l3"});
    add_output(f, "omega", {w[0], w[1], w[2]}, {"omega1", "omega2", "omega3"});
    add_output(f, "mass_matrix", flat(spec.inertia), matrix_names("I"));
    if (quaternion) {
        std::vector<ex> A;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                A.push_back(R[3 * j + i]);
        add_output(f, "rotation", A, matrix_names("A"));
    } else {
        f.unavailable["rotation"] =
            "this body has no orientation-dependent torque, so its state is omega "
            "alone; ask for rotation to keep the quaternion";
    }
    f.unavailable["ignored_rates"] = "only the reduced form ignores coordinates";
}

} // namespace

std::vector<ex> jacobian(const form_expressions& f) {
    return jacobian(f, f.rates);
}

std::vector<ex> jacobian(const form_expressions& f, const std::vector<ex>& rates) {
    const std::size_t n = f.state.size();
    std::vector<ex> J(n * n);
    const auto d = [](const ex& e, const ex& x) { return e.diff(GiNaC::ex_to<GiNaC::symbol>(x)); };
    const bool solve = f.form == form_kind::lagrangian && f.strategy == lagrangian_strategy::solve;
    for (std::size_t i = 0; i < n; ++i) {
        if (solve && i >= 3) continue;
        for (std::size_t k = 0; k < n; ++k)
            J[i * n + k] = d(rates[i], f.state[k].symbol);
    }
    if (solve) {
        // d q_ddot / d y_k = M^{-1} (df/dy_k - dM/dy_k q_ddot), with the factorisation of the rhs.
        const ldlt F = ldlt_factor(f.mass);
        const vec qdd{rates[3], rates[4], rates[5]};
        for (std::size_t k = 0; k < n; ++k) {
            const ex& y = f.state[k].symbol;
            vec r;
            bool zero = true;
            for (int i = 0; i < 3; ++i) {
                r[i] = d(f.forcing[i], y);
                for (int j = 0; j < 3; ++j)
                    r[i] -= d(f.mass[i][j], y) * qdd[j];
                zero = zero && r[i].is_zero();
            }
            const vec c = zero ? vec{0, 0, 0} : ldlt_solve(F, r);
            for (int i = 0; i < 3; ++i)
                J[(3 + i) * n + k] = c[i];
        }
    }
    return J;
}

form_expressions build_form(const model_spec& spec, const derivation& d, form_kind form,
                            lagrangian_strategy strategy, bool orientation) {
    form_expressions f;
    f.form = form;
    f.strategy = strategy;
    f.time = symbols().t;
    f.parameters = model_parameters(spec);
    switch (form) {
    case form_kind::lagrangian:
        lagrangian(spec, d, f);
        break;
    case form_kind::hamiltonian:
        hamiltonian(spec, d, f);
        break;
    case form_kind::reduced:
        reduced(spec, d, f);
        break;
    case form_kind::body:
        body(spec, d, f, orientation);
        break;
    }
    if (form == form_kind::lagrangian || form == form_kind::hamiltonian) {
        add_output(f, "mass_matrix", flat(d.mass_matrix), matrix_names("M"));
        const auto A = rotation_matrix();
        add_output(f, "rotation", std::vector<ex>(A.begin(), A.end()), matrix_names("A"));
        f.unavailable["ignored_rates"] = "only the reduced form ignores coordinates";
    }
    return f;
}

} // namespace rotgen
