// rotgen — forms/: the body form, y = (qw, qx, qy, qz, omega1, omega2, omega3), no Euler angles:
//   I omega_dot = tau - omega x I omega  (Euler's equations (5.87)-(5.89), full tensor),
//   q_dot = 1/2 q (x) (0, omega)         (quaternion kinematics, body angular velocity).
// R(q) = A^T (body -> space), A of (5.25); every use of q divides by |q|^2. The gravity torque is
// r_com x (-M g e), e the space vertical in body axes (R's third row, smooth everywhere); other
// potentials, damping and torques in the angles go through the Euler-angle chart (angles from q),
// singular at theta = 0, pi. Without an orientation-dependent torque y = (omega1, omega2, omega3)
// unless the orientation is asked for.
#include "forms/form_algebra.hpp"

#include "expr/angles.hpp"
#include "expr/symbols.hpp"

namespace rotgen::form_detail {

using GiNaC::ex;

namespace {

// R(q) = A^T (body -> space), row-major, divided by |q|^2 so that it is a rotation for any q != 0.
std::array<ex, 9> rotation_of_quaternion() {
    const auto& Q = quaternion_symbols();
    const ex qw = Q[0], qx = Q[1], qy = Q[2], qz = Q[3];
    const ex n2 = qw * qw + qx * qx + qy * qy + qz * qz;
    return {(qw * qw + qx * qx - qy * qy - qz * qz) / n2,
            2 * (qx * qy - qw * qz) / n2,
            2 * (qx * qz + qw * qy) / n2,
            2 * (qx * qy + qw * qz) / n2,
            (qw * qw - qx * qx + qy * qy - qz * qz) / n2,
            2 * (qy * qz - qw * qx) / n2,
            2 * (qx * qz - qw * qy) / n2,
            2 * (qy * qz + qw * qx) / n2,
            (qw * qw - qx * qx - qy * qy + qz * qz) / n2};
}

// The Euler-angle chart, for whatever is only known in angles. With R = A^T = R_a(alpha) R_b(beta)
// R_c(gamma) (sequence a-b-c, d the third axis, e = +-1 its parity; runtime/euler_sequence.hpp):
//   proper Euler: sin beta = |(R_ab, R_ad)|, cos beta = R_aa, alpha = atan2(R_ba, -e R_da),
//                 gamma = atan2(R_ab, e R_ad);
//   Tait-Bryan:   cos beta = |(R_aa, R_ab)|, sin beta = e R_ac, alpha = atan2(-e R_bc, R_cc),
//                 gamma = atan2(-e R_ab, R_aa).
// For z-x-z: R20 = sin(theta) sin(psi), R21 = sin(theta) cos(psi), R22 = cos(theta), R02 = sin(phi)
// sin(theta), R12 = -cos(phi) sin(theta). The rates q_dot = J^{-1} omega.
class euler_chart {
  public:
    euler_chart(const std::array<ex, 9>& R, const derivation& d, const vec& w) {
        const auto& s = symbols();
        const angle_convention& c = d.angles;
        const auto r = [&R](int i, int j) { return R[3 * i + j]; };
        const int a = c.axes[0], b = c.axes[1], cc = c.axes[2], o = 3 - a - b;
        const ex e = (b - a + 3) % 3 == 1 ? 1 : -1;
        std::array<ex, 6> yx; // atan2 arguments (y, x) of alpha, beta, gamma
        std::array<ex, 3> scale;
        if (c.proper()) {
            const ex sb = GiNaC::sqrt(r(a, b) * r(a, b) + r(a, o) * r(a, o));
            yx = {r(b, a), -e * r(o, a), sb, r(a, a), r(a, b), e * r(a, o)};
            scale = {sb, 1, sb};
        } else {
            const ex cb = GiNaC::sqrt(r(a, a) * r(a, a) + r(a, b) * r(a, b));
            yx = {-e * r(b, cc), r(cc, cc), e * r(a, cc), cb, -e * r(a, b), r(a, a)};
            scale = {cb, 1, cb};
        }
        for (int i = 0; i < 3; ++i) {
            const std::string n = c.names[i];
            const GiNaC::realsymbol ps("rg_sin_" + n), pc("rg_cos_" + n);
            m_trig_value[ps] = yx[2 * i] / scale[i];
            m_trig_value[pc] = yx[2 * i + 1] / scale[i];
            m_to_place[GiNaC::sin(s.q[i])] = ps;
            m_to_place[GiNaC::cos(s.q[i])] = pc;
            m_angle_value[s.q[i]] = GiNaC::atan2(yx[2 * i], yx[2 * i + 1]);
        }
        const vec qdot = mat_vec(d.inverse_omega_jacobian, w); // q_dot = J^{-1} omega
        for (int i = 0; i < 3; ++i)
            m_rates[s.qd[i]] = qdot[i];
    }

    // x in the body form's state: rates from omega, angles (sin, cos) from q. An x with neither
    // is returned as it is and does not count as a use of the chart.
    ex operator()(const ex& x) {
        const auto& s = symbols();
        ex y = x.subs(m_rates);
        if (y.is_equal(x) && !x.has(s.q[0]) && !x.has(s.q[1]) && !x.has(s.q[2])) return x;
        m_used = true;
        return y.subs(m_to_place).subs(m_angle_value).subs(m_trig_value);
    }

    bool used() const { return m_used; }

  private:
    GiNaC::exmap m_trig_value, m_to_place, m_angle_value, m_rates;
    bool m_used = false;
};

// The gravity shorthand's potential, as the spec stage builds it: M g (com . e), e the third
// column of A ((sin theta sin psi, sin theta cos psi, cos theta) for z-x-z).
ex gravity_potential(const model_spec& spec) {
    if (!spec.gravity) return 0;
    const ex_matrix3 A = rotation_of_angles(spec.angles);
    ex h = 0;
    for (int i = 0; i < 3; ++i)
        h += spec.gravity->com[i] * A[i][2];
    return spec.gravity->mass * spec.gravity->g * h;
}

struct body_torque {
    vec tau{0, 0, 0};
    ex potential = 0; // V in the body form's state
    bool needs_orientation = false;
};

// Gravity in closed form: tau = r_com x (-M g e), V = M g (r_com . e).
void add_gravity(const model_spec& spec, const vec& e, body_torque& b) {
    if (!spec.gravity) return;
    const vec r{spec.gravity->com[0], spec.gravity->com[1], spec.gravity->com[2]};
    const ex Mg = spec.gravity->mass * spec.gravity->g;
    const vec c = cross(r, e);
    for (int i = 0; i < 3; ++i)
        b.tau[i] += -Mg * c[i]; // r_com x (-M g e)
    b.needs_orientation = true;
}

// The rest of the potential through the chart: tau = -J^{-T} dV/dq.
void add_other_potential(const derivation& d, euler_chart& chart, const ex& v_rest,
                         body_torque& b) {
    if (v_rest.is_zero()) return;
    const auto& s = symbols();
    vec dv;
    for (int i = 0; i < 3; ++i)
        dv[i] = v_rest.diff(s.q[i]);
    const vec t = mat_t_vec(d.inverse_omega_jacobian, dv);
    for (int i = 0; i < 3; ++i)
        b.tau[i] += chart(-t[i]);
    b.potential += chart(v_rest);
    b.needs_orientation = true;
}

// Damping: the generalised force -c q_dot as a torque J^{-T} Q, through the chart.
void add_damping(const model_spec& spec, const derivation& d, euler_chart& chart, body_torque& b) {
    if (!spec.has_damping) return;
    const auto& s = symbols();
    vec q;
    for (int i = 0; i < 3; ++i)
        q[i] = -spec.damping[i] * s.qd[i];
    const vec t = mat_t_vec(d.inverse_omega_jacobian, q);
    bool zero = true;
    for (int i = 0; i < 3; ++i)
        zero = zero && t[i].expand().is_zero();
    if (zero) return;
    for (int i = 0; i < 3; ++i)
        b.tau[i] += chart(t[i]);
    b.needs_orientation = true;
}

// The body-frame torque of the model; through the chart where it mentions angles or rates.
void add_applied_torque(const model_spec& spec, euler_chart& chart, body_torque& b) {
    if (!spec.has_torque) return;
    for (int i = 0; i < 3; ++i) {
        const ex t = chart(spec.torque[i]);
        if (!t.is_equal(spec.torque[i])) b.needs_orientation = true;
        b.tau[i] += t;
    }
}

// The torque-driven wheels' reaction -sum tau_k a_k (derive/wheels.hpp), through the chart where
// the torques mention angles or rates.
void add_motor_reaction(const derivation& d, euler_chart& chart, body_torque& b) {
    if (!d.wheels.torqued) return;
    for (int i = 0; i < 3; ++i) {
        const ex t = chart(d.wheels.motor[i]);
        if (!t.is_equal(d.wheels.motor[i])) b.needs_orientation = true;
        b.tau[i] += t;
    }
}

body_torque torque_of(const model_spec& spec, const derivation& d, const vec& e,
                      euler_chart& chart) {
    body_torque b;
    add_gravity(spec, e, b);
    const ex v_rest = (spec.potential - gravity_potential(spec)).expand();
    if (spec.gravity) {
        ex h = 0;
        for (int i = 0; i < 3; ++i)
            h += spec.gravity->com[i] * e[i];
        b.potential = spec.gravity->mass * spec.gravity->g * h;
    }
    add_other_potential(d, chart, v_rest, b);
    add_damping(spec, d, chart, b);
    add_applied_torque(spec, chart, b);
    add_motor_reaction(d, chart, b);
    return b;
}

// The state (q if kept, then omega) and its rates: q_dot = 1/2 q (x) (0, omega),
// omega_dot = I^{-1} (tau - omega x I omega).
void body_state_and_rates(const model_spec& spec, const derivation& d, const vec& w, const vec& tau,
                          bool quaternion, form_expressions& f) {
    const auto& s = symbols();
    const auto& Q = quaternion_symbols();
    if (quaternion)
        for (int i = 0; i < 4; ++i)
            f.state.push_back(
                {Q[i].get_name(), Q[i], "orientation quaternion (body -> space), any norm"});
    for (int i = 0; i < 3; ++i)
        f.state.push_back(
            {"omega" + std::to_string(i + 1), s.omega[i], "body angular velocity, rad/time"});
    if (quaternion) {
        const ex qw = Q[0], qx = Q[1], qy = Q[2], qz = Q[3];
        const std::array<ex, 4> qd{
            (-qx * w[0] - qy * w[1] - qz * w[2]) / 2, (qw * w[0] + qy * w[2] - qz * w[1]) / 2,
            (qw * w[1] + qz * w[0] - qx * w[2]) / 2, (qw * w[2] + qx * w[1] - qy * w[0]) / 2};
        for (int i = 0; i < 4; ++i) {
            f.rates.push_back(qd[i]);
            f.rate_names.push_back(Q[i].get_name() + "_dot");
        }
    }
    const vec Iw = mat_vec(spec.inertia, w);
    const vec gyro = cross(w, momentum_of(d, Iw)); // omega x (I omega + h), h of the wheels
    vec rhs;
    for (int i = 0; i < 3; ++i)
        rhs[i] = d.wheels.driven ? tau[i] - gyro[i] - d.wheels.h_dot[i] : tau[i] - gyro[i];
    const vec wd = mat_vec(d.inverse_inertia, rhs);
    for (int i = 0; i < 3; ++i) {
        f.rates.push_back(wd[i]);
        f.rate_names.push_back("omega" + std::to_string(i + 1) + "_dot");
    }
}

// "qz(phi) (x) qx(theta) (x) qz(psi)" for the model's sequence and names.
std::string quaternion_of_angles_text(const angle_convention& c) {
    std::string t;
    for (int i = 0; i < 3; ++i)
        t += (i ? " (x) q" : "q") + std::string(1, "xyz"[c.axes[i]]) + "(" + c.names[i] + ")";
    return t;
}

void body_notes(const model_spec& spec, bool quaternion, bool chart_used, form_expressions& f) {
    f.notes.push_back(
        "I omega_dot = tau - omega x I omega (Euler's equations (5.87)-(5.89) for a full tensor "
        "with torque)" +
        std::string(quaternion ? "; q_dot = 1/2 q (x) (0, omega)." : "."));
    if (quaternion)
        f.notes.push_back(
            "q = (qw, qx, qy, qz) rotates body axes into space axes: R(q) = A^T with A of "
            "(5.25); from Euler angles q = " +
            quaternion_of_angles_text(spec.angles) +
            ". Every use divides by |q|^2, so q need not stay normalised.");
    if (spec.gravity)
        f.notes.push_back(
            "gravity torque r_com x (-M g e), e = third row of R(q): no singularity.");
    f.uses_euler_chart = chart_used;
    if (chart_used)
        f.notes.push_back(
            "WARNING: part of the torque or potential is known only in Euler angles and is "
            "evaluated through the chart (angles from q): singular at " +
            spec.angles.singular_text() + ".");
}

// energy T + V with T = 1/2 omega . I omega; l = I omega; omega; I; A = R^T if q is kept.
void body_outputs(const model_spec& spec, const derivation& d, const vec& w, const ex& potential,
                  const std::array<ex, 9>& R, bool quaternion, form_expressions& f) {
    const vec Iw = mat_vec(spec.inertia, w);
    add_output(f, "energy", {kinetic_of(d, w, Iw) + potential}, {"energy"});
    const vec l = momentum_of(d, Iw);
    add_output(f, "momenta", {l[0], l[1], l[2]}, {"l1", "l2", "l3"});
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

void build_body(const model_spec& spec, const derivation& d, form_expressions& f,
                bool orientation) {
    const auto& s = symbols();
    const vec w{s.omega[0], s.omega[1], s.omega[2]};
    const std::array<ex, 9> R = rotation_of_quaternion();
    const vec e{R[6], R[7], R[8]}; // the space vertical in body axes: A's third column
    euler_chart chart(R, d, w);
    const body_torque torque = torque_of(spec, d, e, chart);
    const bool quaternion = torque.needs_orientation || orientation;
    body_state_and_rates(spec, d, w, torque.tau, quaternion, f);
    add_wheel_states(spec, f, [&chart](const ex& e) { return chart(e); });
    body_notes(spec, quaternion, chart.used(), f);
    body_outputs(spec, d, w, torque.potential, R, quaternion, f);
}

} // namespace rotgen::form_detail
