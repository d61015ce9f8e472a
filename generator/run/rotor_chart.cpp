// rotgen — run/: the rotor's charts (rotor_chart.hpp).
#include "run/rotor_chart.hpp"

#include "derive/rotor.hpp"
#include "expr/numbers.hpp"
#include "expr/symbols.hpp"
#include "support/format.hpp"

#include <cmath>

namespace rotgen {

namespace {

struct direction {
    Eigen::Vector3d m, m_dot; // in the chart's own (permuted) components
};

// m = (sin theta sin phi, -sin theta cos phi, cos theta), m_dot = dm/dq q_dot.
direction of_angles(double phi, double theta, double phi_dot, double theta_dot) {
    const double sp = std::sin(phi), cp = std::cos(phi), st = std::sin(theta), ct = std::cos(theta);
    direction d;
    d.m = {st * sp, -st * cp, ct};
    d.m_dot = {ct * sp * theta_dot + st * cp * phi_dot, -ct * cp * theta_dot + st * sp * phi_dot,
               -st * theta_dot};
    return d;
}

// The inverse: theta = atan2(rho, m3), phi = atan2(m1, -m2), rho = sqrt(m1^2 + m2^2) = sin theta,
// phi_dot = (m1 m2' - m2 m1') / rho^2 (d atan2(y, x) = (x dy - y dx) / (x^2 + y^2)),
// theta_dot = -m3' / rho (m3 = cos theta).
Eigen::VectorXd angles_of(const direction& d) {
    const Eigen::Vector3d& m = d.m;
    const Eigen::Vector3d& md = d.m_dot;
    const double rho2 = m[0] * m[0] + m[1] * m[1], rho = std::sqrt(rho2);
    Eigen::VectorXd y(4);
    y << std::atan2(m[0], -m[1]), std::atan2(rho, m[2]), (m[0] * md[1] - m[1] * md[0]) / rho2,
        -md[2] / rho;
    return y;
}

// n from chart 2's m = (n_y, n_z, n_x), and back.
Eigen::Vector3d unpermute(const Eigen::Vector3d& m) {
    return {m[2], m[0], m[1]};
}
Eigen::Vector3d permute(const Eigen::Vector3d& n) {
    return {n[1], n[2], n[0]};
}

} // namespace

bool is_rotor_form(form_kind f) {
    return f == form_kind::rotor || f == form_kind::rotor_x;
}

form_kind other_chart(form_kind scene_form) {
    return is_rotor_form(scene_form) ? form_kind::rotor_x : form_kind::body;
}

bool rotor_can_switch(const scene_spec& scene) {
    return scene.switch_chart && rotor_potential_in_chart2(scene.model).has_value();
}

initial_kinematics rotor_initial_kinematics(const scene_spec& scene) {
    const scoped_digits digits(30);
    GiNaC::exmap at;
    const model_spec& spec = scene.model;
    for (std::size_t i = 0; i < spec.parameters.size(); ++i)
        at[spec.parameters[i].symbol] = exact_scene_value(
            scene.parameters[i],
            i < scene.parameters_written.size() ? scene.parameters_written[i] : written_value{});
    const long double I = to_long_double(spec.rotor_moment.subs(at));
    initial_kinematics k;
    for (std::size_t i = 0; i < 2; ++i) {
        k.q[i] = to_long_double(exact_scene_value(scene.angles[i], scene.angles_written[i]));
        k.qd[i] = to_long_double(exact_scene_value(scene.initial_rates[i], scene.rates_written[i]));
    }
    const long double st = std::sin(k.q[1]);
    k.p = {I * st * st * k.qd[0], I * k.qd[1], 0};
    k.have_rates = true;
    k.quat = Eigen::Quaternion<long double>(1, 0, 0, 0); // unused: a rotor has no quaternion
    return k;
}

Eigen::VectorXd rotor_state(form_kind form, const initial_kinematics& k) {
    Eigen::VectorXd y(4);
    y << double(k.q[0]), double(k.q[1]), double(k.qd[0]), double(k.qd[1]);
    return form == form_kind::rotor ? y : rotor_other_chart(form_kind::rotor, y);
}

double rotor_sin_theta(form_kind form, const Eigen::VectorXd& y) {
    if (form == form_kind::rotor) return std::abs(std::sin(y[1]));
    const Eigen::Vector3d n = unpermute(of_angles(y[0], y[1], y[2], y[3]).m);
    return std::hypot(n[0], n[1]);
}

Eigen::VectorXd rotor_other_chart(form_kind from, const Eigen::VectorXd& y) {
    direction d = of_angles(y[0], y[1], y[2], y[3]);
    if (from == form_kind::rotor)
        d = {permute(d.m), permute(d.m_dot)};
    else
        d = {unpermute(d.m), unpermute(d.m_dot)};
    return angles_of(d);
}

std::string rotor_pole_message(double theta) {
    return "initial theta = " + format_number(theta) +
           " is the pole of the rotor's angles (sin theta = 0, where phi is undefined), and this "
           "run cannot continue in the second chart (switch_chart: false, or a potential that "
           "depends on more than cos(theta)); start away from the pole";
}

} // namespace rotgen
