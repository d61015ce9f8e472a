#include "run/chart_kinematics.hpp"

#include "run/angle_chart.hpp"
#include "run/rotor_chart.hpp"

#include <rotgen.hpp> // runtime: quaternion_from_euler, euler_from_quaternion

#include <cmath>

namespace rotgen {

// The initial kinematics of a continuation in the body form from an Euler-angle state (q, q_dot
// from f): omega = J q_dot (5.30).
initial_kinematics continuation(const euler_sequence& s, const Eigen::VectorXd& y,
                                const Eigen::VectorXd& dydt) {
    initial_kinematics k;
    for (int i = 0; i < 3; ++i)
        k.q[i] = y[i], k.qd[i] = dydt[i];
    if (s.is_zxz()) {
        const double st = std::sin(y[1]), ct = std::cos(y[1]), sp = std::sin(y[2]),
                     cp = std::cos(y[2]);
        const double qd0 = dydt[0], qd1 = dydt[1], qd2 = dydt[2];
        k.omega = {qd0 * st * sp + qd1 * cp, qd0 * st * cp - qd1 * sp, qd0 * ct + qd2};
    } else {
        const Eigen::Vector3d w = omega_jacobian_at<double>(s, {y[0], y[1], y[2]}) * dydt.head<3>();
        k.omega = {w[0], w[1], w[2]};
    }
    const Eigen::Quaterniond q = quaternion_of_angles(s, double(y[0]), double(y[1]), double(y[2]));
    k.quat = Eigen::Quaternion<long double>(q.w(), q.x(), q.y(), q.z());
    return k;
}

// The initial kinematics in the Euler-angle chart from a body-form state (quaternion, omega):
// q_dot = J^{-1} omega, p = J^T I omega (5.30); needs the chart distance away from 0.
initial_kinematics from_body(const euler_sequence& s, const Eigen::VectorXd& y,
                             const Eigen::Matrix3d& inertia) {
    const std::array<double, 3> e =
        angles_of_quaternion(s, Eigen::Quaterniond(y[0], y[1], y[2], y[3]));
    initial_kinematics k;
    k.q = {e[0], e[1], e[2]};
    const Eigen::Vector3d w(y[4], y[5], y[6]), l = inertia * w;
    if (s.is_zxz()) {
        const double st = std::sin(e[1]), ct = std::cos(e[1]), sp = std::sin(e[2]),
                     cp = std::cos(e[2]);
        const double phi_dot = (w[0] * sp + w[1] * cp) / st;
        k.qd = {phi_dot, w[0] * cp - w[1] * sp, w[2] - phi_dot * ct};
        k.p = {st * sp * l[0] + st * cp * l[1] + ct * l[2], cp * l[0] - sp * l[1], l[2]};
    } else {
        const Eigen::Matrix3d J = omega_jacobian_at(s, e);
        const Eigen::Vector3d qd = J.lu().solve(w), p = J.transpose() * l;
        k.qd = {qd[0], qd[1], qd[2]};
        k.p = {p[0], p[1], p[2]};
    }
    k.omega = {w[0], w[1], w[2]};
    k.quat = Eigen::Quaternion<long double>(y[0], y[1], y[2], y[3]);
    return k;
}

// The chart distance (|sin theta| for z-x-z) of a state of the given form (Euler-angle forms:
// the middle angle is y[1]).
double sin_theta_of(const euler_sequence& s, form_kind form, const Eigen::VectorXd& y) {
    if (is_rotor_form(form)) return rotor_sin_theta(form, y);
    if (form != form_kind::body) return chart_distance(s, y[1]);
    return chart_distance(s,
                          angles_of_quaternion(s, Eigen::Quaterniond(y[0], y[1], y[2], y[3]))[1]);
}

bool sin_theta_below(const euler_sequence& s, form_kind form, const Eigen::VectorXd& y,
                     double bound) {
    const double beta = y[1];
    if ((form == form_kind::lagrangian || form == form_kind::hamiltonian) && std::abs(beta) < 1e6) {
        // r: the distance of the middle angle from a singular angle (a multiple of pi, proper
        // sequences; of pi plus pi/2, Tait-Bryan) good to 1e-9, the nearest one but where x / pi
        // is within rounding of a half (then r is about pi/2, and |sin| about 1, either way); and
        // sin r >= (2/pi) r on [0, pi/2], so r > (pi/2) bound + 1e-6 means |sin| > bound
        const double pi = 3.14159265358979323846;
        const double x = s.proper() ? beta : beta - pi / 2;
        const double q = x * (1 / pi); // the nearest integer by a cast (no libm call)
        const double k = static_cast<double>(static_cast<long long>(q + (q < 0 ? -0.5 : 0.5)));
        if (std::abs(x - pi * k) > pi / 2 * bound + 1e-6) return false;
    }
    return sin_theta_of(s, form, y) < bound;
}

} // namespace rotgen
