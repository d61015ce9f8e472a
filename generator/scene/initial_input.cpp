#include "scene/initial_input.hpp"

#include "expr/angles.hpp"
#include "expr/numbers.hpp"
#include "expr/symbols.hpp"
#include "lower/lower_form.hpp" // exact_decimal
#include "support/format.hpp"

#include <cmath>

namespace rotgen::scene_detail {

using GiNaC::ex;

namespace {

enum attitude_kind { by_angles, by_quaternion, by_matrix };

class initial_reader {
  public:
    initial_reader(scene_spec& scene, const YAML::Node& n, const value_reader& values,
                   const std::string& file)
        : m_scene(scene), m_n(n), m_values(values), m_file(file) {
        const auto& q = m_scene.model.angles.names;
        m_attitude = {{{q[0], q[1], q[2]}, {"q0", "q1", "q2", "q3"}, {"A"}}};
        m_rates = {{{q[0] + "_dot", q[1] + "_dot", q[2] + "_dot"},
                    {"p_" + q[0], "p_" + q[1], "p_" + q[2]},
                    {"omega1", "omega2", "omega3"},
                    {"omega_x", "omega_y", "omega_z"}}};
    }

    void read(const source_location& key) {
        std::vector<std::string> allowed;
        for (const auto& g : m_attitude)
            allowed.insert(allowed.end(), g.begin(), g.end());
        for (const auto& g : m_rates)
            allowed.insert(allowed.end(), g.begin(), g.end());
        for (const auto& p : m_scene.model.parameters) // free wheels: scene/wheel_initial.cpp
            if (p.wheel_momentum) {                    // p_<wheel> or <wheel>_dot
                allowed.push_back(p.name);
                allowed.push_back(p.name.substr(2) + "_dot");
            }
        check_keys(m_n, allowed, m_file, "initial");
        const int att = chosen(m_attitude, "give the attitude one way only: the angles, a "
                                           "quaternion q0..q3 or the matrix A");
        const int rates = chosen(m_rates, "give the initial rates one way only: angle rates, "
                                          "momenta, body omega or space omega");
        check_complete(key, att, rates);
        if (att != by_angles && rates == 1)
            throw user_error(at(m_n[m_rates[1][0]]), "momenta need the attitude as the angles (" +
                                                         angle_list() +
                                                         "): they are conjugate to them");
        const ex_matrix3 A = attitude(static_cast<attitude_kind>(att));
        read_rates(rates, A);
    }

  private:
    source_location at(const YAML::Node& x) const { return location_of(x, m_file); }

    std::string angle_list() const {
        const auto& q = m_scene.model.angles.names;
        return q[0] + ", " + q[1] + ", " + q[2];
    }

    // The group whose keys the mapping uses (-1: none); an error at a key of a second group.
    template <class Groups> int chosen(const Groups& groups, const std::string& once) const {
        int c = -1;
        for (int g = 0; g < static_cast<int>(groups.size()); ++g)
            for (const auto& key : groups[static_cast<std::size_t>(g)])
                if (m_n[key]) {
                    if (c >= 0 && c != g) throw user_error(at(m_n[key]), once);
                    c = g;
                }
        return c;
    }

    void check_complete(const source_location& key, int att, int rates) const {
        std::vector<std::string> missing;
        for (const auto& name : m_attitude[static_cast<std::size_t>(att < 0 ? 0 : att)])
            if (!m_n[name]) missing.push_back(name);
        if (rates >= 0)
            for (const auto& name : m_rates[static_cast<std::size_t>(rates)])
                if (!m_n[name]) missing.push_back(name);
        if (missing.empty() && rates >= 0) return;
        std::string list;
        for (const auto& name : missing)
            list += (list.empty() ? "" : ", ") + name;
        const auto& r = m_rates;
        std::string attitude;
        for (const auto& name : m_attitude[static_cast<std::size_t>(att < 0 ? 0 : att)])
            attitude += (attitude.empty() ? "" : ", ") + name;
        const std::string why =
            rates >= 0
                ? " (a state is " + attitude + " with " + r[static_cast<std::size_t>(rates)][0] +
                      ", " + r[static_cast<std::size_t>(rates)][1] + ", " +
                      r[static_cast<std::size_t>(rates)][2] + "; nothing defaults to 0)"
                : std::string(list.empty() ? "" : " and ") + "the rates (" + r[0][0] + ", " +
                      r[0][1] + ", " + r[0][2] + ", or " + r[1][0] + ", " + r[1][1] + ", " +
                      r[1][2] +
                      ", or omega1, omega2, omega3, or omega_x, omega_y, omega_z; nothing "
                      "defaults to 0)";
        throw user_error(key, "the initial state is incomplete: missing " + list + why);
    }

    static ex exact_of(const written_value& w) {
        return w.expression ? w.exact : ex(exact_decimal(w.value));
    }

    static written_value written_exact(const ex& e) {
        const scoped_digits digits(40);
        written_value w;
        w.exact = e;
        w.expression = true;
        w.value = GiNaC::ex_to<GiNaC::numeric>(e.evalf()).to_double();
        return w;
    }

    ex_matrix3 attitude(attitude_kind kind) {
        const angle_convention& c = m_scene.model.angles;
        if (kind == by_angles) {
            GiNaC::exmap at;
            const auto& q = c.names;
            for (std::size_t i = 0; i < 3; ++i) {
                m_scene.angles_written[i] = m_values.value(m_n[q[i]], "initial " + q[i]);
                m_scene.angles[i] = m_scene.angles_written[i].value;
                at[symbols().q[i]] = exact_of(m_scene.angles_written[i]);
            }
            check_middle_angle();
            ex_matrix3 A = rotation_of_angles(c);
            for (auto& row : A)
                for (auto& x : row)
                    x = x.subs(at, GiNaC::subs_options::no_pattern);
            return A;
        }
        const ex_matrix3 A = kind == by_quaternion ? quaternion_matrix() : given_matrix();
        const std::array<ex, 3> angles = angles_of_matrix(A, c);
        for (std::size_t i = 0; i < 3; ++i) {
            m_scene.angles_written[i] = written_exact(angles[i]);
            m_scene.angles[i] = m_scene.angles_written[i].value;
        }
        return A;
    }

    // The middle angle of angles written by hand: [0, pi] (proper Euler), [-pi/2, pi/2]
    // (Tait-Bryan).
    void check_middle_angle() const {
        const angle_convention& c = m_scene.model.angles;
        const double b = m_scene.angles[1], pi = 3.141592653589793238;
        const bool ok = c.proper() ? b >= 0 && b <= pi : b >= -pi / 2 && b <= pi / 2;
        if (!ok)
            throw user_error(at(m_n[c.names[1]]), "initial " + c.names[1] + " = " +
                                                      format_double(b) + " is outside " +
                                                      (c.proper() ? "[0, pi]" : "[-pi/2, pi/2]") +
                                                      " (" + c.description() + ")");
    }

    ex_matrix3 quaternion_matrix() const;
    ex_matrix3 given_matrix() const;
    void read_rates(int group, const ex_matrix3& A);

    scene_spec& m_scene;
    const YAML::Node& m_n;
    const value_reader& m_values;
    const std::string& m_file;
    std::array<std::vector<std::string>, 3> m_attitude;
    std::array<std::vector<std::string>, 4> m_rates;
};

// A = R(q)^T / |q|^2 (rotation.hpp's matrix_from_quaternion), exact in the values written.
ex_matrix3 initial_reader::quaternion_matrix() const {
    std::array<ex, 4> q;
    ex n2 = 0;
    for (std::size_t i = 0; i < 4; ++i) {
        const std::string key = "q" + std::to_string(i);
        q[i] = exact_of(m_values.value(m_n[key], "initial " + key));
        n2 += q[i] * q[i];
    }
    const double norm = std::sqrt(GiNaC::ex_to<GiNaC::numeric>(n2.evalf()).to_double());
    if (!(std::abs(norm - 1) <= 1e-6))
        throw user_error(at(m_n["q0"]), "the initial quaternion (q0, q1, q2, q3) has norm " +
                                            short_number(norm, 10) +
                                            ", not 1 (to 1e-6): give a unit quaternion");
    const ex w = q[0], x = q[1], y = q[2], z = q[3];
    const ex R[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                        {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                        {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
    ex_matrix3 A;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            A[i][j] = (R[j][i] / n2).expand();
    return A;
}

// A: three rows of three, orthonormal with det +1 to 1e-9.
ex_matrix3 initial_reader::given_matrix() const {
    const YAML::Node a = m_n["A"];
    const std::string shape = "initial A must be three rows of three numbers, row i the body "
                              "axis i in space axes";
    if (!a.IsSequence() || a.size() != 3) throw user_error(at(a), shape);
    ex_matrix3 A;
    double v[3][3];
    for (std::size_t i = 0; i < 3; ++i) {
        if (!a[i].IsSequence() || a[i].size() != 3) throw user_error(at(a[i]), shape);
        for (std::size_t j = 0; j < 3; ++j) {
            const written_value w = m_values.value(a[i][j], "initial A");
            A[i][j] = exact_of(w);
            v[i][j] = w.value;
        }
    }
    double worst = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double d = i == j ? -1.0 : 0.0;
            for (int k = 0; k < 3; ++k)
                d += v[i][k] * v[j][k];
            worst = std::max(worst, std::abs(d));
        }
    const double det = v[0][0] * (v[1][1] * v[2][2] - v[1][2] * v[2][1]) -
                       v[0][1] * (v[1][0] * v[2][2] - v[1][2] * v[2][0]) +
                       v[0][2] * (v[1][0] * v[2][1] - v[1][1] * v[2][0]);
    if (!(worst <= 1e-9) || !(det > 0))
        throw user_error(at(a), "initial A is not a rotation (|A A^T - 1| = " +
                                    short_number(worst) + ", det A = " + short_number(det) +
                                    "; it must be orthonormal to 1e-9 with det +1)");
    return A;
}

// The rates as written, or body omega = A omega_space.
void initial_reader::read_rates(int group, const ex_matrix3& A) {
    const auto& keys = m_rates[static_cast<std::size_t>(group)];
    m_scene.initial = group == 3 ? initial_kind::omega : static_cast<initial_kind>(group);
    std::array<written_value, 3> w;
    for (std::size_t i = 0; i < 3; ++i)
        w[i] = m_values.value(m_n[keys[i]], "initial " + keys[i]);
    if (group == 3) {
        std::array<ex, 3> space;
        for (std::size_t i = 0; i < 3; ++i)
            space[i] = exact_of(w[i]);
        for (std::size_t i = 0; i < 3; ++i)
            w[i] = written_exact(
                (A[i][0] * space[0] + A[i][1] * space[1] + A[i][2] * space[2]).expand());
    }
    for (std::size_t i = 0; i < 3; ++i) {
        m_scene.rates_written[i] = w[i];
        m_scene.initial_rates[i] = w[i].value;
    }
}

} // namespace

void read_initial_state(scene_spec& scene, const YAML::Node& n, const source_location& key,
                        const value_reader& values, const std::string& file) {
    initial_reader(scene, n, values, file).read(key);
}

} // namespace rotgen::scene_detail
