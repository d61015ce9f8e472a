// rotgen — the model's Euler-angle sequence and the names of its angles.
//
// A sequence a-b-c (axes 0 = x, 1 = y, 2 = z) turns α about the space axis a, β about the new b,
// γ about the newest c; the passive matrix (body <- space) is A = A_c(γ) A_b(β) A_a(α), as (5.25)
// is for the chapter's z-x-z, which is the default (phi, theta, psi). The twelve sequences: proper
// Euler zxz zyz xyx xzx yxy yzy (singular where sin β = 0: β = 0, π) and Tait-Bryan zyx zxy yxz
// yzx xyz xzy (singular where cos β = 0: β = ±π/2).
//
// Default names: phi, theta, psi for every sequence but zyx, whose angles are yaw, pitch, roll.
//
// The derivation keeps the one set of coordinate symbols of symbols.hpp (q[0..2] are α, β, γ of
// whatever sequence); the convention is a value of the model (model_spec::angles), carried by the
// derivation, the forms, the scene and the run, and passed to every function that parses or
// prints a name or converts angles: two models with two conventions can be derived and run at
// once in one process (as Pinocchio's algorithms take the model they work on).
#pragma once

#include <ginac/ginac.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace rotgen {

struct angle_convention {
    std::array<int, 3> axes{2, 0, 2};
    std::array<std::string, 3> names{"phi", "theta", "psi"};

    std::string sequence() const; // "zxz"
    bool proper() const { return axes[0] == axes[2]; }
    bool is_zxz() const { return axes[0] == 2 && axes[1] == 0 && axes[2] == 2; }
    // The chapter's convention exactly: z-x-z named phi, theta, psi.
    bool is_default() const;
    // "theta = 0, pi" / "pitch = -pi/2, pi/2": where the chart is singular.
    std::string singular_text() const;
    // "sin(theta)" / "cos(pitch)": the factor that vanishes there.
    std::string singular_factor() const;
    // "z-x-z Euler angles" / "z-y-x Tait-Bryan angles".
    std::string description() const;
    // "singular at theta = 0, pi through 1/sin(theta)"
    std::string singular_clause() const;
    // "0 < theta < pi" / "-pi/2 < pitch < pi/2": the chart's open range of the middle angle.
    std::string regular_range() const;
    // "phi about z, theta about the new x, psi about the new z; phi, psi in [0, 2 pi), theta in
    // [0, pi]"
    std::string axes_text() const;
    // "Az(psi) Ax(theta) Az(phi)"
    std::string matrix_text() const;
};

// "zxz" -> {2, 0, 2}; nullopt unless three of x, y, z with no two neighbours equal.
std::optional<std::array<int, 3>> parse_sequence(const std::string& text);

std::array<std::string, 3> default_angle_names(const std::array<int, 3>& axes);

// "p_phi", "p_theta", "p_psi" in c's names.
std::vector<std::string> momentum_names(const angle_convention& c);

// The name a coordinate, rate, acceleration or momentum symbol of expr/symbols.hpp is shown by
// (c's angle names: q[0] -> "yaw", qd[0] -> "yaw_dot", p[0] -> "p_yaw"); any other symbol's own
// name. Its TeX name: the symbol's own for the chapter's names, else built from c's names.
std::string display_name(const GiNaC::symbol& x, const angle_convention& c);
std::string display_tex_name(const GiNaC::symbol& x, const angle_convention& c);

using ex_matrix3 = std::array<std::array<GiNaC::ex, 3>, 3>;

// A_n(x), passive (5.8, 5.9).
ex_matrix3 elementary_rotation(int axis, const GiNaC::ex& angle);

// A(q) = A_c(q[2]) A_b(q[1]) A_a(q[0]) in the coordinate symbols (5.25 for z-x-z).
ex_matrix3 rotation_of_angles(const angle_convention& c);

// J = d omega / d q_dot, omega = J q_dot in body axes: each rate turns about its own axis, carried
// into body axes by the rotations after it, J = [A_c A_b e_a | A_c e_b | e_c] (5.30 for z-x-z).
ex_matrix3 omega_jacobian_of(const angle_convention& c);

// The angles of a passive matrix A with exact (numeric) entries, as exact expressions: the
// formulas of runtime/euler_sequence.hpp (R = A^T, proper: beta = atan2(|(R_ab, R_ad)|, R_aa),
// alpha = atan2(R_ba, -e R_da), gamma = atan2(R_ab, e R_ad); Tait-Bryan: beta = atan2(e R_ac,
// |(R_aa, R_ab)|), alpha = atan2(-e R_bc, R_cc), gamma = atan2(-e R_ab, R_aa)). On the singular
// set (the norm exactly 0) gamma = 0 and alpha is the angle of R R_b(beta)^T = R_a(alpha).
// alpha, gamma in (-pi, pi].
std::array<GiNaC::ex, 3> angles_of_matrix(const ex_matrix3& A, const angle_convention& c);

} // namespace rotgen
