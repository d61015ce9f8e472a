#include "expr/angles.hpp"

#include "expr/symbols.hpp"

namespace rotgen {

using GiNaC::ex;

namespace {
const char* const axis_letter = "xyz";
} // namespace

std::string angle_convention::sequence() const {
    return {axis_letter[axes[0]], axis_letter[axes[1]], axis_letter[axes[2]]};
}

bool angle_convention::is_default() const {
    return is_zxz() && names == std::array<std::string, 3>{"phi", "theta", "psi"};
}

std::string angle_convention::singular_text() const {
    return proper() ? names[1] + " = 0, pi" : names[1] + " = -pi/2, pi/2";
}

std::string angle_convention::singular_factor() const {
    return (proper() ? "sin(" : "cos(") + names[1] + ")";
}

std::string angle_convention::description() const {
    const std::string s = sequence();
    return std::string{s[0], '-', s[1], '-', s[2]} +
           (proper() ? " Euler angles" : " Tait-Bryan angles");
}

std::string angle_convention::singular_clause() const {
    return "singular at " + singular_text() + " through 1/" + singular_factor();
}

std::string angle_convention::regular_range() const {
    return proper() ? "0 < " + names[1] + " < pi" : "-pi/2 < " + names[1] + " < pi/2";
}

std::string angle_convention::axes_text() const {
    const std::string s = sequence();
    const std::string range =
        proper() ? names[0] + ", " + names[2] + " in [0, 2 pi), " + names[1] + " in [0, pi]"
                 : names[0] + ", " + names[2] + " in (-pi, pi], " + names[1] + " in [-pi/2, pi/2]";
    return names[0] + " about " + s[0] + ", " + names[1] + " about the new " + s[1] + ", " +
           names[2] + " about the new " + s[2] + "; " + range;
}

std::string angle_convention::matrix_text() const {
    const std::string s = sequence();
    return std::string("A") + s[2] + "(" + names[2] + ") A" + s[1] + "(" + names[1] + ") A" + s[0] +
           "(" + names[0] + ")";
}

std::optional<std::array<int, 3>> parse_sequence(const std::string& text) {
    if (text.size() != 3) return std::nullopt;
    std::array<int, 3> axes{};
    for (int i = 0; i < 3; ++i) {
        const char c = text[static_cast<std::size_t>(i)];
        if (c < 'x' || c > 'z') return std::nullopt;
        axes[static_cast<std::size_t>(i)] = c - 'x';
    }
    if (axes[0] == axes[1] || axes[1] == axes[2]) return std::nullopt;
    return axes;
}

std::array<std::string, 3> default_angle_names(const std::array<int, 3>& axes) {
    if (axes == std::array<int, 3>{2, 1, 0}) return {"yaw", "pitch", "roll"};
    return {"phi", "theta", "psi"};
}

ex_matrix3 elementary_rotation(int axis, const ex& angle) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    ex_matrix3 m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m[i][j] = i == j ? ex(1) : ex(0);
    m[u][u] = m[v][v] = GiNaC::cos(angle);
    m[u][v] = GiNaC::sin(angle);
    m[v][u] = -GiNaC::sin(angle);
    return m;
}

namespace {
ex_matrix3 product(const ex_matrix3& a, const ex_matrix3& b) {
    ex_matrix3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            ex s = 0;
            for (int k = 0; k < 3; ++k)
                s += a[i][k] * b[k][j];
            r[i][j] = s.expand();
        }
    return r;
}
} // namespace

ex_matrix3 rotation_of_angles(const angle_convention& c) {
    const auto& s = symbols();
    return product(
        product(elementary_rotation(c.axes[2], s.q[2]), elementary_rotation(c.axes[1], s.q[1])),
        elementary_rotation(c.axes[0], s.q[0]));
}

ex_matrix3 omega_jacobian_of(const angle_convention& c) {
    const auto& s = symbols();
    const ex_matrix3 Ac = elementary_rotation(c.axes[2], s.q[2]);
    const ex_matrix3 AcAb = product(Ac, elementary_rotation(c.axes[1], s.q[1]));
    ex_matrix3 J;
    for (int i = 0; i < 3; ++i) {
        J[i][0] = AcAb[i][c.axes[0]];
        J[i][1] = Ac[i][c.axes[1]];
        J[i][2] = i == c.axes[2] ? ex(1) : ex(0);
    }
    return J;
}

std::array<ex, 3> angles_of_matrix(const ex_matrix3& A, const angle_convention& c) {
    const auto R = [&A](int i, int j) { return A[j][i]; };
    const int a = c.axes[0], b = c.axes[1], cc = c.axes[2], d = 3 - a - b;
    const ex e = (b - a + 3) % 3 == 1 ? 1 : -1;
    std::array<ex, 3> q;
    ex norm;
    if (c.proper()) {
        norm = GiNaC::sqrt((R(a, b) * R(a, b) + R(a, d) * R(a, d)).expand());
        q = {GiNaC::atan2(R(b, a), -e * R(d, a)), GiNaC::atan2(norm, R(a, a)),
             GiNaC::atan2(R(a, b), e * R(a, d))};
    } else {
        norm = GiNaC::sqrt((R(a, a) * R(a, a) + R(a, b) * R(a, b)).expand());
        q = {GiNaC::atan2(-e * R(b, cc), R(cc, cc)), GiNaC::atan2(e * R(a, cc), norm),
             GiNaC::atan2(-e * R(a, b), R(a, a))};
    }
    if (!norm.is_zero()) return q;
    const bool up =
        GiNaC::ex_to<GiNaC::numeric>((c.proper() ? R(a, a) : e * R(a, cc)).evalf()).is_positive();
    q[1] = c.proper() ? (up ? ex(0) : ex(GiNaC::Pi)) : (up ? GiNaC::Pi / 2 : -GiNaC::Pi / 2);
    const ex_matrix3 Ab = elementary_rotation(b, q[1]);
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    ex m_vu = 0, m_uu = 0; // (R A_b(beta))_vu, (R A_b(beta))_uu
    for (int k = 0; k < 3; ++k) {
        m_vu += R(v, k) * Ab[k][u];
        m_uu += R(u, k) * Ab[k][u];
    }
    q[0] = GiNaC::atan2(m_vu.expand(), m_uu.expand());
    q[2] = 0;
    return q;
}

} // namespace rotgen
