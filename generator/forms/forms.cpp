// rotgen — forms/: the public entry points of forms.hpp: build_form (which dispatches to
// lagrangian.cpp, hamiltonian.cpp, reduced.cpp and body.cpp), the analytic jacobian, the rotation
// matrix A (5.25), the quaternion symbols and the output names.
#include "forms/forms.hpp"

#include "expr/angles.hpp"
#include "expr/symbols.hpp"
#include "forms/form_algebra.hpp"

namespace rotgen {

using GiNaC::ex;
using namespace form_detail;

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
    static const std::vector<std::string> names{"rhs",      "jacobian",      "energy",
                                                "momenta",  "mass_matrix",   "omega",
                                                "rotation", "ignored_rates", "taylor"};
    return names;
}

std::array<ex, 9> rotation_matrix(const angle_convention& c) {
    // (5.25): A = A_c(gamma) A_b(beta) A_a(alpha) for the model's sequence a-b-c, Az(psi) Ax(theta)
    // Az(phi) for z-x-z, Az(a) = [[c, s, 0], [-s, c, 0], [0, 0, 1]], Ax(a) = [[1, 0, 0], [0, c, s],
    // [0, -s, c]] (5.8, 5.9); expr/angles.hpp.
    const ex_matrix3 A = rotation_of_angles(c);
    std::array<ex, 9> r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r[3 * i + j] = A[i][j];
    return r;
}

std::vector<ex> jacobian(const form_expressions& f) {
    return jacobian(f, f.rates);
}

namespace {

ex d_by(const ex& e, const ex& x) {
    return e.diff(GiNaC::ex_to<GiNaC::symbol>(x));
}

// The solve strategy's rows 3..5 of d rates / d x_k for the variables x (J row-major, one column
// per variable): d q_ddot / d x_k = M^{-1} (df/dx_k - dM/dx_k q_ddot), with the factorisation of
// the rhs.
void solve_rows(const form_expressions& f, const std::vector<ex>& rates,
                const std::vector<ex>& variables, std::vector<ex>& J) {
    const std::size_t m = variables.size();
    const ldlt F = ldlt_factor(f.mass);
    const vec qdd{rates[3], rates[4], rates[5]};
    for (std::size_t k = 0; k < m; ++k) {
        const ex& x = variables[k];
        vec r;
        bool zero = true;
        for (int i = 0; i < 3; ++i) {
            r[i] = d_by(f.forcing[i], x);
            for (int j = 0; j < 3; ++j)
                r[i] -= d_by(f.mass[i][j], x) * qdd[j];
            zero = zero && r[i].is_zero();
        }
        const vec c = zero ? vec{0, 0, 0} : ldlt_solve(F, r);
        for (int i = 0; i < 3; ++i)
            J[(3 + i) * m + k] = c[i];
    }
}

// d rates_i / d x_k, row-major (rates x variables), the solve strategy's rows by solve_rows.
std::vector<ex> derivatives(const form_expressions& f, const std::vector<ex>& rates,
                            const std::vector<ex>& variables) {
    const std::size_t n = rates.size(), m = variables.size();
    std::vector<ex> J(n * m);
    const bool solve = f.form == form_kind::lagrangian && f.strategy == lagrangian_strategy::solve;
    for (std::size_t i = 0; i < n; ++i) {
        if (solve && i >= 3 && i < 6) continue; // 6..: a torque-driven wheel's p, by diff
        for (std::size_t k = 0; k < m; ++k)
            J[i * m + k] = d_by(rates[i], variables[k]);
    }
    if (solve) solve_rows(f, rates, variables, J);
    return J;
}

std::vector<form_parameter> model_parameters(const model_spec& spec) {
    std::vector<form_parameter> ps;
    for (const parameter& p : spec.parameters)
        ps.push_back({p.name, p.symbol, p.value, p.description, !p.wheel_momentum});
    return ps;
}

} // namespace

std::vector<ex> jacobian(const form_expressions& f, const std::vector<ex>& rates) {
    std::vector<ex> state;
    for (const auto& s : f.state)
        state.push_back(s.symbol);
    return derivatives(f, rates, state);
}

std::vector<ex> parameter_jacobian(const form_expressions& f, const std::vector<ex>& rates,
                                   const std::vector<ex>& parameters) {
    return derivatives(f, rates, parameters);
}

form_expressions build_form(const model_spec& model, const derivation& d, form_kind form,
                            lagrangian_strategy strategy, bool orientation) {
    const model_spec spec = gyrostat_body(model); // I + J a a^T of rate-driven wheels
    form_expressions f;
    f.angles = spec.angles;
    f.form = form;
    f.strategy = strategy;
    f.time = symbols().t;
    f.parameters = model_parameters(spec);
    refuse_torque_wheels_in(model, form);
    switch (form) {
    case form_kind::lagrangian:
        build_lagrangian(spec, d, f);
        break;
    case form_kind::hamiltonian:
        build_hamiltonian(spec, d, f);
        break;
    case form_kind::reduced:
        build_reduced(spec, d, f);
        break;
    case form_kind::body:
        build_body(spec, d, f, orientation);
        break;
    case form_kind::rotor:
    case form_kind::rotor_x:
        build_rotor(spec, f, form == form_kind::rotor ? 1 : 2);
        break;
    }
    if (form == form_kind::lagrangian || form == form_kind::hamiltonian) {
        add_output(f, "mass_matrix", flat(d.mass_matrix), matrix_names("M"));
        const auto A = rotation_matrix(spec.angles);
        add_output(f, "rotation", std::vector<ex>(A.begin(), A.end()), matrix_names("A"));
        f.unavailable["ignored_rates"] = "only the reduced form ignores coordinates";
    }
    return f;
}

} // namespace rotgen
