#include "run/actions.hpp"

#include "expr/symbols.hpp"
#include "run/angle_chart.hpp"
#include "run/chart_kinematics.hpp"
#include "run/prepared.hpp" // symbolic_mutex
#include "support/error.hpp"
#include "support/format.hpp"

#include <cmath>
#include <mutex>

namespace rotgen {

namespace {

// An action on a gyrostat forms the state from body omega with the wheels keeping their momenta
// p_k: right for free wheels in the Lagrangian and body forms (Delta omega = I^-1 J, I without
// the wheels' axial moments); the Hamiltonian form's momenta and a driven wheel's inertia would
// need h, which the action's kinematics (from_body) do not carry.
void refuse_wheel_action(const scene_spec& scene, const event_spec& e) {
    bool driven = false;
    for (const wheel_spec& w : scene.model.wheels)
        driven = driven || w.drive != wheel_spec::drive_kind::free;
    if (scene.model.wheels.empty() || (!driven && scene.form != form_kind::hamiltonian)) return;
    throw user_error(e.action_where,
                     "event '" + e.name + "': an action on a model with wheels needs free wheels " +
                         "and the lagrangian or body form" +
                         (driven ? " (a wheel here is driven)" : ", not hamiltonian"));
}

using vec3 = Eigen::Vector3d;

// The kinematics before an action: the attitude and body omega of any form's state, with the
// angles, rates and momenta (p = J^T I omega, 5.30) an expression may use. An Euler-angle form
// keeps its own angles and rates (no wrap of phi, psi).
initial_kinematics before_of(const euler_sequence& seq, const action_state& s,
                             const Eigen::Matrix3d& inertia) {
    Eigen::VectorXd yb(7);
    if (s.form == form_kind::body) {
        yb = s.y.head<7>();
    } else {
        const initial_kinematics c = continuation(seq, s.y, s.dydt);
        yb << double(c.quat.w()), double(c.quat.x()), double(c.quat.y()), double(c.quat.z()),
            double(c.omega[0]), double(c.omega[1]), double(c.omega[2]);
    }
    yb.head<4>().normalize();
    initial_kinematics k = from_body(seq, yb, inertia);
    if (s.form != form_kind::body)
        for (int i = 0; i < 3; ++i)
            k.q[i] = s.y[i], k.qd[i] = s.dydt[i];
    return k;
}

Eigen::Quaterniond quat_of(const initial_kinematics& k) {
    return Eigen::Quaterniond(double(k.quat.w()), double(k.quat.x()), double(k.quat.y()),
                              double(k.quat.z()));
}

vec3 vec_of(const std::array<long double, 3>& a) {
    return vec3(double(a[0]), double(a[1]), double(a[2]));
}

// The values of an action's expressions at the state before it (GiNaC, under the lock).
class evaluator {
  public:
    evaluator(const scene_spec& scene, const initial_kinematics& k, double t,
              const std::vector<long double>& parameters) {
        const coordinate_symbols& s = symbols();
        for (int i = 0; i < 3; ++i) {
            m_map[s.q[i]] = double(k.q[i]), m_map[s.qd[i]] = double(k.qd[i]);
            m_map[s.p[i]] = double(k.p[i]), m_map[s.omega[i]] = double(k.omega[i]);
        }
        m_map[s.t] = t;
        for (std::size_t i = 0; i < parameters.size(); ++i)
            m_map[scene.model.parameters[i].symbol] = double(parameters[i]);
    }
    // The value, or NaN when it is not a finite real number.
    double operator()(const GiNaC::ex& e) const {
        const GiNaC::ex v = GiNaC::evalf(e.subs(m_map));
        if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
            return std::nan("");
        return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
    }

  private:
    GiNaC::exmap m_map;
};

int index_in(const std::vector<std::string>& names, const std::string& name) {
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return static_cast<int>(i);
    return -1;
}

// The set of one event, applied to the state before it (all values taken before any is set).
class set_action {
  public:
    set_action(const event_spec& e, const model_spec& model, const euler_sequence& seq,
               const Eigen::Matrix3d& inertia)
        : m_e(e), m_model(model), m_c(model.angles), m_seq(seq), m_inertia(inertia) {}

    // The new attitude and body omega; error: a located message.
    std::string apply(const evaluator& value, const initial_kinematics& before,
                      std::vector<long double>& parameters, Eigen::Quaterniond& quat,
                      std::array<double, 3>& angles, vec3& w) const {
        std::vector<std::vector<double>> v;
        for (const set_entry& s : m_e.set) {
            v.emplace_back();
            for (const auto& x : s.values)
                v.back().push_back(value(x));
            for (double x : v.back())
                if (!std::isfinite(x))
                    return located(s.where, "the value of " + s.name + " is not finite");
        }
        if (std::string why = attitude(v, quat, angles); !why.empty()) return why;
        velocity(before, v, quat, angles, w);
        for (std::size_t i = 0; i < m_e.set.size(); ++i)
            if (m_e.set[i].name.rfind("parameters.", 0) == 0)
                for (std::size_t p = 0; p < parameters.size(); ++p)
                    if ("parameters." + m_model.parameters[p].name == m_e.set[i].name)
                        parameters[p] = v[i][0];
        return "";
    }

  private:
    // Where the first of `names` is set.
    const source_location& first_of(const std::vector<std::string>& names) const {
        for (const set_entry& s : m_e.set)
            if (index_in(names, s.name) >= 0) return s.where;
        return m_e.action_where;
    }

    std::string located(const source_location& at, const std::string& what) const {
        return to_string(at) + ": event '" + m_e.name + "': " + what;
    }

    std::string attitude(const std::vector<std::vector<double>>& v, Eigen::Quaterniond& quat,
                         std::array<double, 3>& angles) const {
        const std::vector<std::string> q = {"q0", "q1", "q2", "q3"};
        Eigen::Vector4d qv(quat.w(), quat.x(), quat.y(), quat.z());
        bool by_angles = false, by_quat = false;
        for (std::size_t i = 0; i < m_e.set.size(); ++i) {
            const std::string& name = m_e.set[i].name;
            if (const int a = index_in({m_c.names[0], m_c.names[1], m_c.names[2]}, name); a >= 0)
                angles[a] = v[i][0], by_angles = true;
            if (const int j = index_in(q, name); j >= 0) qv[j] = v[i][0], by_quat = true;
            if (name != "A") continue;
            Eigen::Matrix3d A;
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    A(r, c) = v[i][static_cast<std::size_t>(3 * r + c)];
            const double off =
                (A * A.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
            if (off > 1e-9 || A.determinant() < 0)
                return located(m_e.set[i].where,
                               "A is not a rotation (|A A^T - 1| = " + short_number(off) +
                                   ", det " + short_number(A.determinant()) + ")");
            quat = Eigen::Quaterniond(Eigen::Matrix3d(A.transpose())).normalized();
            angles = angles_of_quaternion(m_seq, quat);
        }
        if (by_angles) quat = quaternion_of_angles(m_seq, angles[0], angles[1], angles[2]);
        if (by_quat) {
            if (std::abs(qv.norm() - 1) > 1e-6)
                return located(first_of(q), "the quaternion set has norm " +
                                                format_number(qv.norm()) + ", not 1 (to 1e-6)");
            qv.normalize();
            quat = Eigen::Quaterniond(qv[0], qv[1], qv[2], qv[3]);
            angles = angles_of_quaternion(m_seq, quat);
        }
        return "";
    }

    void velocity(const initial_kinematics& before, const std::vector<std::vector<double>>& v,
                  const Eigen::Quaterniond& quat, const std::array<double, 3>& angles,
                  vec3& w) const {
        const auto& n = m_c.names;
        const std::vector<std::vector<std::string>> ways = {
            {n[0] + "_dot", n[1] + "_dot", n[2] + "_dot"},
            {"p_" + n[0], "p_" + n[1], "p_" + n[2]},
            {"omega1", "omega2", "omega3"},
            {"omega_x", "omega_y", "omega_z"}};
        const Eigen::Quaterniond q_before = quat_of(before);
        std::array<vec3, 4> value = {vec_of(before.qd), vec_of(before.p), vec_of(before.omega),
                                     q_before * vec_of(before.omega)};
        int way = -1;
        for (std::size_t i = 0; i < m_e.set.size(); ++i)
            for (int g = 0; g < 4; ++g)
                if (const int j = index_in(ways[g], m_e.set[i].name); j >= 0)
                    value[g][j] = v[i][0], way = g;
        const Eigen::Matrix3d J = omega_jacobian_at<double>(m_seq, angles);
        if (way == 0) w = J * value[0];                                             // (5.30)
        if (way == 1) w = m_inertia.inverse() * J.transpose().inverse() * value[1]; // p = J^T I w
        if (way == 2) w = value[2];
        if (way == 3) w = quat.conjugate() * value[3]; // omega = A omega_space
    }

    const event_spec& m_e;
    const model_spec& m_model;
    const angle_convention& m_c;
    const euler_sequence& m_seq;
    const Eigen::Matrix3d& m_inertia;
};

} // namespace

bool has_actions(const scene_spec& scene) {
    for (const event_spec& e : scene.events)
        if (e.acts() || e.periodic || e.after > 1) return true;
    return false;
}

run_actions::run_actions(const scene_spec& scene, const euler_sequence& sequence,
                         const std::vector<long double>& model_parameters)
    : m_scene(scene), m_sequence(sequence), m_period(scene.events.size(), 0),
      m_seen(scene.events.size(), 0), m_counted(scene.events.size(), 0) {
    if (!has_actions(scene)) return;
    const std::lock_guard<std::mutex> lock(symbolic_mutex());
    GiNaC::exmap values;
    for (std::size_t i = 0; i < model_parameters.size(); ++i)
        values[scene.model.parameters[i].symbol] = double(model_parameters[i]);
    for (std::size_t i = 0; i < scene.events.size(); ++i) {
        const event_spec& e = scene.events[i];
        if (scene.t_end < scene.t_start && (e.acts() || e.periodic))
            throw user_error(e.periodic ? e.where : e.action_where,
                             "event '" + e.name +
                                 "': actions and time events are refused in a backward run "
                                 "(time end before start)");
        if (e.acts() && scene.form != form_kind::lagrangian &&
            scene.form != form_kind::hamiltonian && scene.form != form_kind::body)
            throw user_error(e.action_where, "event '" + e.name +
                                                 "': an action needs the lagrangian, "
                                                 "hamiltonian or body form, not " +
                                                 to_string(scene.form));
        if (e.acts()) refuse_wheel_action(scene, e);
        if (!e.periodic) continue;
        const GiNaC::ex T = GiNaC::evalf(e.every.subs(values));
        m_period[i] = GiNaC::is_a<GiNaC::numeric>(T) ? GiNaC::ex_to<GiNaC::numeric>(T).to_double()
                                                     : std::nan("");
        if (!(m_period[i] > 0) || !std::isfinite(m_period[i]))
            throw user_error(e.where, "event '" + e.name + "': 'every' is " +
                                          format_number(m_period[i]) +
                                          " at this member's parameters; it must be > 0");
    }
}

bool run_actions::terminal(std::size_t i) const {
    const event_spec& e = m_scene.events[i];
    return e.acts() || e.stop;
}

bool run_actions::occurs(std::size_t i) {
    if (++m_seen[i] < static_cast<std::size_t>(m_scene.events[i].after)) return false;
    ++m_counted[i];
    return true;
}

std::optional<std::pair<double, std::size_t>> run_actions::next_time(double t, double t_end) const {
    std::optional<std::pair<double, std::size_t>> first;
    for (std::size_t i = 0; i < m_period.size(); ++i) {
        if (m_period[i] == 0) continue;
        const double origin = m_scene.events[i].every_origin, T = m_period[i];
        double k = std::max(1.0, std::floor((t - origin) / T));
        while (origin + k * T <= t)
            k += 1;
        while (k > 1 && origin + (k - 1) * T > t)
            k -= 1;
        const double tk = origin + k * T;
        if (tk < t_end && (!first || tk < first->first)) first = std::make_pair(tk, i);
    }
    return first;
}

action_outcome run_actions::apply(std::size_t i, const action_state& s,
                                  const Eigen::Matrix3d& inertia,
                                  std::vector<long double>& parameters) const {
    const event_spec& e = m_scene.events[i];
    const initial_kinematics before = before_of(m_sequence, s, inertia);
    Eigen::Quaterniond quat = quat_of(before);
    std::array<double, 3> angles = {double(before.q[0]), double(before.q[1]), double(before.q[2])};
    vec3 w = vec_of(before.omega);
    action_outcome out;
    {
        const std::lock_guard<std::mutex> lock(symbolic_mutex());
        const evaluator value(m_scene, before, s.t, parameters);
        if (e.action == action_kind::set) {
            const set_action set(e, m_scene.model, m_sequence, inertia);
            out.error = set.apply(value, before, parameters, quat, angles, w);
        } else {
            vec3 J(value(e.impulse[0]), value(e.impulse[1]), value(e.impulse[2]));
            if (!J.allFinite())
                out.error = to_string(e.action_where) + ": event '" + e.name +
                            "': the impulse is not finite";
            if (e.action == action_kind::impulse_space) J = quat.conjugate() * J; // A J_space
            w += inertia.inverse() * J;                                           // Delta L = J
        }
    }
    if (!out.error.empty()) return out;
    Eigen::VectorXd yb(7);
    yb << quat.w(), quat.x(), quat.y(), quat.z(), w[0], w[1], w[2];
    out.k = from_body(m_sequence, yb, inertia);
    for (int a = 0; a < 3; ++a)
        out.k.q[a] = angles[a]; // the angles kept or set (no wrap), the same attitude
    return out;
}

} // namespace rotgen
