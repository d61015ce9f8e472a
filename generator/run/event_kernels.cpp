#include "run/event_kernels.hpp"

#include "expr/angles.hpp"
#include "expr/symbols.hpp"
#include "run/kernels.hpp"
#include "support/error.hpp"

#include <optional>

namespace rotgen {

namespace {

using GiNaC::ex;

// Any sequence: the angles of A (expr/angles.hpp), q_dot = J^{-1} omega and p = J^T I omega with
// J (5.30 for z-x-z) at those angles; singular where the chart is.
std::optional<ex> sequence_euler_value(const scene_spec& scene, const std::vector<ex>& a,
                                       const std::array<ex, 3>& w, const std::string& name) {
    ex_matrix3 A;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            A[i][j] = a[static_cast<std::size_t>(3 * i + j)];
    const angle_convention& c = scene.model.angles;
    const std::array<ex, 3> q = angles_of_matrix(A, c);
    GiNaC::exmap at;
    for (int i = 0; i < 3; ++i)
        at[symbols().q[i]] = q[i];
    ex_matrix3 J = omega_jacobian_of(c);
    for (auto& row : J)
        for (auto& x : row)
            x = x.subs(at);
    const auto& I = scene.model.inertia;
    const auto& n = c.names;
    const ex det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                   J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                   J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
    for (int i = 0; i < 3; ++i) {
        if (name == n[i]) return q[i];
        if (name == "p_" + n[i]) {
            ex p = 0;
            for (int k = 0; k < 3; ++k)
                p += J[k][i] * (I[k][0] * w[0] + I[k][1] * w[1] + I[k][2] * w[2]);
            return p;
        }
        if (name == n[i] + "_dot") { // Cramer's rule: column i of J replaced by omega
            ex_matrix3 Ji = J;
            for (int k = 0; k < 3; ++k)
                Ji[k][i] = w[k];
            return (Ji[0][0] * (Ji[1][1] * Ji[2][2] - Ji[1][2] * Ji[2][1]) -
                    Ji[0][1] * (Ji[1][0] * Ji[2][2] - Ji[1][2] * Ji[2][0]) +
                    Ji[0][2] * (Ji[1][0] * Ji[2][1] - Ji[1][1] * Ji[2][0])) /
                   det;
        }
    }
    return std::nullopt;
}

// The Euler-angle quantities of the body form from its rotation matrix and omega (header).
std::optional<ex> body_euler_value(const scene_spec& scene, const form_expressions& f,
                                   const std::string& name) {
    const auto rot = f.outputs.find("rotation");
    const auto w1 = form_value(f, "omega1"), w2 = form_value(f, "omega2"),
               w3 = form_value(f, "omega3");
    if (f.form != form_kind::body || rot == f.outputs.end() || !w1 || !w2 || !w3)
        return std::nullopt;
    const std::vector<ex>& a = rot->second.values; // row-major A
    if (!scene.model.angles.is_zxz()) return sequence_euler_value(scene, a, {*w1, *w2, *w3}, name);
    const ex a13 = a[2], a23 = a[5], a31 = a[6], a32 = a[7], a33 = a[8];
    const ex sin2 = a13 * a13 + a23 * a23, sin_theta = GiNaC::sqrt(sin2);
    const ex phi_dot = (*w1 * a13 + *w2 * a23) / sin2;
    if (name == "theta") return GiNaC::acos(a33);
    if (name == "phi") return GiNaC::atan2(a31, -a32);
    if (name == "psi") return GiNaC::atan2(a13, a23);
    if (name == "phi_dot") return phi_dot;
    if (name == "theta_dot") return (*w1 * a23 - *w2 * a13) / sin_theta;
    if (name == "psi_dot") return *w3 - phi_dot * a33;
    const auto& I = scene.model.inertia; // l = I omega
    const ex w[3] = {*w1, *w2, *w3};
    ex l[3];
    for (int i = 0; i < 3; ++i)
        l[i] = I[i][0] * w[0] + I[i][1] * w[1] + I[i][2] * w[2];
    if (name == "p_phi") return a13 * l[0] + a23 * l[1] + a33 * l[2];
    if (name == "p_theta") return (a23 * l[0] - a13 * l[1]) / sin_theta;
    if (name == "p_psi") return l[2];
    return std::nullopt;
}

bool is_parameter(const form_expressions& f, const ex& symbol) {
    for (const auto& p : f.parameters)
        if (p.symbol.is_equal(symbol)) return true;
    return symbol.is_equal(f.time);
}

} // namespace

std::vector<ex> event_programs(const scene_spec& scene, const form_expressions& f) {
    const name_table names = event_names(scene.model);
    std::vector<ex> programs;
    for (const event_spec& e : scene.events) {
        GiNaC::exmap in_state;
        for (const auto& [name, symbol] : names) {
            if (!e.when.has(symbol) || is_parameter(f, symbol)) continue;
            std::optional<ex> value = form_value(f, name);
            if (!value) value = body_euler_value(scene, f, name);
            if (!value)
                throw user_error(e.where, "event '" + e.name + "': the " +
                                              std::string(to_string(f.form)) +
                                              " form does not give '" + name + "'");
            in_state[symbol] = *value;
        }
        programs.push_back(e.when.subs(in_state));
    }
    return programs;
}

} // namespace rotgen
