#include "inspect/inspect.hpp"

#include "expr/angles.hpp"
#include "expr/print.hpp"
#include "expr/symbols.hpp"
#include "inertia/inertia.hpp"
#include "inspect/equations.hpp"
#include "inspect/wheels.hpp"

#include <algorithm>
#include <sstream>

namespace rotgen {

using GiNaC::ex;

std::string json_quote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        switch (c) {
        case '"':
            out += "\\\"";
            break;
        case '\\':
            out += "\\\\";
            break;
        case '\n':
            out += "\\n";
            break;
        case '\t':
            out += "\\t";
            break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char buf[8];
                std::snprintf(buf, sizeof buf, "\\u%04x", c);
                out += buf;
            } else {
                out += c;
            }
        }
    }
    return out + "\"";
}

namespace {

std::string json_array(const vector3& v, const angle_convention& c) {
    std::string s = "[";
    for (int i = 0; i < 3; ++i)
        s += (i ? ", " : "") + json_quote(to_text(v[i], c));
    return s + "]";
}

// ---- the inertia report (--inertia)
// ---------------------------------------------------------------

std::string short_number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
}

// An exact value with its number at the defaults ("9/11 = 0.818182", "I1 = 1"); a numeric one
// (from the eigensolver) as its number alone.
std::string with_value(const GiNaC::ex& e, double value, const angle_convention& c) {
    if (GiNaC::is_a<GiNaC::numeric>(e)) {
        const auto& n = GiNaC::ex_to<GiNaC::numeric>(e);
        if (!n.is_rational()) return short_number(value);
        return to_text(e, c) + (n.is_integer() ? "" : " = " + short_number(value));
    }
    return to_text(e, c) + " = " + short_number(value);
}

std::string text_vector(const vector3& v, const angle_convention& c) {
    return "(" + to_text(v[0], c) + ", " + to_text(v[1], c) + ", " + to_text(v[2], c) + ")";
}

std::string class_description(top_class c) {
    switch (c) {
    case top_class::spherical:
        return "spherical top (I1 = I2 = I3)";
    case top_class::symmetric:
        return "symmetric top (two equal principal moments)";
    case top_class::asymmetric:
        return "asymmetric top (three different principal moments)";
    case top_class::rotor:
        return "rotor (one principal moment zero, the other two equal)";
    }
    return "";
}

// A rate in closed form in the parameters (not a plain number): its expression is shown only
// with --symbolic (parts give expressions of kilobytes), its value at the defaults always.
bool symbolic_rate(const axis_stability& s) {
    return !GiNaC::is_a<GiNaC::numeric>(s.rate);
}

std::string rate_text(const axis_stability& s, bool symbolic, const angle_convention& c) {
    return symbolic || !symbolic_rate(s) ? with_value(s.rate, s.rate_value, c)
                                         : short_number(s.rate_value);
}

// One line per principal axis: what a small deviation from steady rotation about it does.
std::string stability_text(const axis_stability& s, const inertia_report& r, bool symbolic,
                           const angle_convention& c) {
    const std::string n = std::to_string(s.axis);
    switch (s.kind) {
    case stability_kind::stable:
        if (s.rate_value == 0)
            return "stable: omega stays constant (" +
                   std::string(r.kind == top_class::rotor ? "any axis across a rotor is principal"
                                                          : "all moments equal") +
                   ")";
        return "stable: small deviations oscillate at Omega" + n + " = " +
               rate_text(s, symbolic, c) + " (5.94)";
    case stability_kind::unstable:
        return "unstable: small deviations grow like exp(Omega" + n + " t), Omega" + n + " = " +
               rate_text(s, symbolic, c) + " (5.100)";
    case stability_kind::neutral:
        return "neutral: Omega" + n +
               "^2 = 0 (equal moments); no oscillation and no exponential "
               "growth, the spin axis drifts in the plane of the equal moments";
    case stability_kind::none:
        return "none: the line of a rotor; rotation about it moves no mass (T = 0)";
    }
    return "";
}

std::string exactness(const principal_axes& p) {
    if (p.exact_axes) return "exact";
    if (p.exact_moments) return "moments exact, axes numeric at the parameters' defaults";
    return "numeric, at the parameters' defaults";
}

std::string inertia_text(const model_spec& spec, const inertia_report& r, bool symbolic) {
    const angle_convention& c = spec.angles;
    std::ostringstream os;
    os << "inertia of " << spec.name << " (" << spec.file << ")\n";
    if (spec.body) {
        const auto& b = *spec.body;
        os << "body: " << spec.parts.size() << (spec.parts.size() == 1 ? " part" : " parts")
           << ", total mass " << to_text(b.mass, c) << ", centre of mass "
           << text_vector(b.centre_of_mass, c) << ", pivot " << text_vector(b.pivot, c)
           << (b.pivot_given ? "" : " (the centre of mass)") << "\n";
    }
    os << "\ntensor " << (spec.body ? "about the pivot" : "about the fixed point")
       << ", body axes (5.39):\n";
    for (int i = 0; i < 3; ++i)
        os << "  " << text_vector(r.tensor[i], c) << "\n";
    os << "\nprincipal moments and axes (" << exactness(r.principal)
       << "; the axes are the rows of A, A I A^T diagonal (5.69)):\n";
    for (int k = 0; k < 3; ++k) {
        os << "  I" << k + 1 << " = "
           << with_value(r.principal.moments[k], r.principal.moment_values[k], c) << "  along "
           << text_vector(r.principal.axes[k], c) << "\n";
    }
    os << "class: " << class_description(r.kind) << "\n";
    if (r.kind == top_class::rotor)
        os << "a linear rotor (Example 5.4): rotation about its line (axis 1) moves no mass, so "
              "its attitude\nhas two angles (phi, theta), with T = 1/2 I (theta_dot^2 + "
              "sin(theta)^2 "
              "phi_dot^2), I = I2 = I3;\nemit and simulate run it in the form rotor\n";
    os << "\nsteady rotation about each principal axis, force-free (5.87-5.89), per unit spin\n"
       << "(rates scale with the spin omega; numbers at the parameters' defaults"
       << (!symbolic && std::any_of(r.stability.begin(), r.stability.end(), symbolic_rate)
               ? "; --symbolic shows their expressions"
               : "")
       << "):\n";
    for (const auto& s : r.stability)
        os << "  axis " << s.axis << ": " << stability_text(s, r, symbolic, c) << "\n";
    os << gyrostat_stability_text(spec, r);
    return os.str();
}

std::string latex_vector(const vector3& v, const angle_convention& c) {
    return "\\left(" + to_latex(v[0], c) + ", " + to_latex(v[1], c) + ", " + to_latex(v[2], c) +
           "\\right)";
}

std::string inertia_latex(const model_spec& spec, const inertia_report& r, bool symbolic) {
    const angle_convention& c = spec.angles;
    std::ostringstream os;
    os << "% rotgen inspect --inertia --format latex: model " << spec.name << " (" << spec.file
       << ")\n";
    os << "% principal axes: rows of A, A I A^T diagonal (5.69); " << exactness(r.principal)
       << "\n";
    os << "\\begin{align*}\n";
    if (spec.body) {
        os << "  M &= " << to_latex(spec.body->mass, c) << " \\\\\n";
        os << "  \\vec{r}_{\\mathrm{cm}} &= " << latex_vector(spec.body->centre_of_mass, c)
           << " \\\\\n";
        os << "  \\vec{r}_{\\mathrm{pivot}} &= " << latex_vector(spec.body->pivot, c) << " \\\\\n";
    }
    os << "  I &= \\begin{pmatrix}";
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            os << " " << to_latex(r.tensor[i][j], c) << (j < 2 ? " &" : i < 2 ? " \\\\" : " ");
    os << "\\end{pmatrix} \\\\\n";
    for (int k = 0; k < 3; ++k)
        os << "  I_{" << k + 1 << "} &= " << to_latex(r.principal.moments[k], c) << ", & \\hat{e}_{"
           << k + 1 << "} &= " << latex_vector(r.principal.axes[k], c) << " \\\\\n";
    for (int k = 0; k < 3; ++k) {
        const auto& s = r.stability[k];
        const std::string rate =
            symbolic || !symbolic_rate(s) ? to_latex(s.rate, c) : short_number(s.rate_value);
        os << "  \\Omega_{" << k + 1 << "} &= " << rate << " \\, \\omega & &\\text{"
           << stability_kind_name(s.kind)
           << (s.kind == stability_kind::stable && s.rate_value != 0 ? " (5.94)"
               : s.kind == stability_kind::unstable                  ? " (5.100)"
                                                                     : "")
           << "}" << (k < 2 ? " \\\\" : "") << "\n";
    }
    os << "\\end{align*}\n";
    os << "% class: " << class_description(r.kind) << "\n";
    return os.str();
}

std::string inertia_json(const model_spec& spec, const inertia_report& r) {
    const angle_convention& c = spec.angles;
    std::ostringstream os;
    const auto matrix = [&c](const matrix3& m) {
        std::string s = "[";
        for (int i = 0; i < 3; ++i)
            s += (i ? ", " : "") + json_array(m[i], c);
        return s + "]";
    };
    os << "  \"inertia\": {\n";
    os << "    \"tensor\": " << matrix(r.tensor) << ",\n";
    os << "    \"principal_moments\": " << json_array(r.principal.moments, c) << ",\n";
    os << "    \"principal_axes\": " << matrix(r.principal.axes) << ",\n";
    os << "    \"class\": " << json_quote(top_class_name(r.kind)) << ",\n";
    os << "    \"stability\": [";
    for (int k = 0; k < 3; ++k) {
        const auto& s = r.stability[k];
        os << (k ? ",\n                  " : "") << "{\"axis\": " << s.axis
           << ", \"stable\": " << (s.stable ? "true" : "false")
           << ", \"rate\": " << format_double(s.rate_value)
           << ", \"kind\": " << json_quote(stability_kind_name(s.kind))
           << ", \"rate_expression\": " << json_quote(to_text(s.rate, c)) << "}";
    }
    os << "],\n    \"exact_moments\": " << (r.principal.exact_moments ? "true" : "false")
       << ",\n    \"exact_axes\": " << (r.principal.exact_axes ? "true" : "false") << ",\n";
    os << "    \"principal_moment_values\": [";
    for (int k = 0; k < 3; ++k)
        os << (k ? ", " : "") << format_double(r.principal.moment_values[k]);
    os << "]";
    if (spec.body) {
        os << ",\n    \"mass\": " << json_quote(to_text(spec.body->mass, c));
        os << ",\n    \"centre_of_mass\": " << json_array(spec.body->centre_of_mass, c);
        os << ",\n    \"pivot\": " << json_array(spec.body->pivot, c);
    }
    os << gyrostat_stability_json(spec, r) << "\n  }";
    return os.str();
}

std::string json_list(const std::vector<ex>& v, const angle_convention& c) {
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i)
        s += (i ? ", " : "") + json_quote(to_text(v[i], c));
    return s + "]";
}

std::string as_json(const model_spec& spec, const equations& d, const inertia_report* inertia) {
    const angle_convention& c = d.angles;
    std::ostringstream os;
    os << "{\n  \"model\": " << json_quote(spec.name) << ",\n  \"parameters\": {";
    for (std::size_t i = 0; i < spec.parameters.size(); ++i)
        os << (i ? ", " : "") << json_quote(spec.parameters[i].name) << ": "
           << format_double(spec.parameters[i].value);
    os << "},\n  \"coordinates\": [";
    for (std::size_t i = 0; i < d.names.size(); ++i)
        os << (i ? ", " : "") << json_quote(d.names[i]);
    os << "],\n";
    if (!spec.rotor) {
        os << "  \"angles\": {\"sequence\": " << json_quote(c.sequence()) << ", \"names\": ["
           << json_quote(c.names[0]) << ", " << json_quote(c.names[1]) << ", "
           << json_quote(c.names[2]) << "]},\n";
    }
    if (!d.omega.empty()) os << "  \"omega\": " << json_list(d.omega, c) << ",\n";
    if (!d.direction.empty()) os << "  \"direction\": " << json_list(d.direction, c) << ",\n";
    os << "  \"kinetic\": " << json_quote(to_text(d.kinetic, c)) << ",\n";
    os << "  \"potential\": " << json_quote(to_text(d.potential, c)) << ",\n";
    os << "  \"lagrangian\": " << json_quote(to_text(d.lagrangian, c)) << ",\n";
    os << "  \"momenta\": " << json_list(d.momenta, c) << ",\n";
    os << "  \"mass_matrix\": [";
    for (std::size_t i = 0; i < d.mass_matrix.size(); ++i)
        os << (i ? ", " : "") << json_list(d.mass_matrix[i], c);
    os << "],\n  \"euler_lagrange\": " << json_list(d.euler_lagrange, c) << ",\n";
    os << "  \"hamiltonian\": " << json_quote(to_text(d.hamiltonian, c)) << ",\n";
    os << "  \"hamilton_equations\": {\"qdot\": " << json_list(d.qdot, c)
       << ", \"pdot\": " << json_list(d.pdot, c) << "},\n";
    os << "  \"cyclic\": [";
    for (std::size_t i = 0; i < d.cyclic.size(); ++i)
        os << (i ? ", " : "") << json_quote(d.names[static_cast<std::size_t>(d.cyclic[i])]);
    os << "],\n  \"energy\": " << json_quote(to_text(d.energy, c)) << wheels_json(spec);
    if (inertia) os << ",\n" << inertia_json(spec, *inertia);
    os << "\n}\n";
    return os.str();
}

std::string as_text(const model_spec& spec, const equations& d) {
    const angle_convention& c = d.angles;
    std::ostringstream os;
    os << "model " << spec.name << " (" << spec.file << ")\n";
    os << "coordinates: " << d.coordinates_note << "\n";
    os << "parameters:";
    if (spec.parameters.empty()) os << " none";
    for (const auto& p : spec.parameters)
        os << " " << p.name << " = " << format_double(p.value);
    if (!d.omega.empty()) os << "\n\nbody angular velocity (5.30):\n";
    for (std::size_t i = 0; i < d.omega.size(); ++i)
        os << "  omega" << i + 1 << " = " << to_text(d.omega[i], c) << "\n";
    if (!d.direction.empty())
        os << "\n\ndirection of the line in space (the third row of A, 5.25):\n";
    for (std::size_t i = 0; i < d.direction.size(); ++i)
        os << "  n"
           << "xyz"[i] << " = " << to_text(d.direction[i], c) << "\n";
    os << "\nkinetic energy   T = " << to_text(d.kinetic, c) << "\n";
    os << "potential energy V = " << to_text(d.potential, c) << "\n";
    os << "Lagrangian       L = " << to_text(d.lagrangian, c) << "\n";
    os << "\ncanonical momenta p = dL/dq_dot:\n";
    const std::size_t n = d.names.size();
    for (std::size_t i = 0; i < n; ++i)
        os << "  p_" << d.names[i] << " = " << to_text(d.momenta[i], c) << "\n";
    os << "\nmass matrix M(q) (symmetric; M q_ddot = f):\n";
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i; j < n; ++j)
            os << "  M[" << d.names[i] << "][" << d.names[j]
               << "] = " << to_text(d.mass_matrix[i][j], c) << "\n";
    os << "\nf(q, q_dot, t):\n";
    for (std::size_t i = 0; i < n; ++i)
        os << "  f_" << d.names[i] << " = " << to_text(d.forcing[i], c) << "\n";
    os << "\nEuler-Lagrange equations (each = 0):\n";
    for (std::size_t i = 0; i < n; ++i)
        os << "  " << to_text(d.euler_lagrange[i], c) << " = 0\n";
    os << "\nHamiltonian H(q, p) = " << to_text(d.hamiltonian, c) << "\n";
    os << "\nHamilton's equations:\n";
    for (std::size_t i = 0; i < n; ++i)
        os << "  " << d.names[i] << "_dot = " << to_text(d.qdot[i], c) << "\n";
    for (std::size_t i = 0; i < n; ++i)
        os << "  p_" << d.names[i] << "_dot = " << to_text(d.pdot[i], c) << "\n";
    os << "\ncyclic coordinates:";
    if (d.cyclic.empty()) os << " none";
    for (int i : d.cyclic)
        os << " " << d.names[static_cast<std::size_t>(i)] << " (p_"
           << d.names[static_cast<std::size_t>(i)] << " conserved)";
    os << "\nenergy E = T + V = " << to_text(d.energy, c) << "\n";
    os << wheels_text(spec);
    return os.str();
}

std::string as_latex(const model_spec& spec, const equations& d) {
    std::ostringstream os;
    const auto tex = [&d](const ex& e) { return to_latex(e, d.angles); };
    os << "% rotgen inspect --format latex: model " << spec.name << " (" << spec.file << ")\n";
    os << "% " << d.latex_note << "\n";
    os << "\\begin{align*}\n";
    for (std::size_t i = 0; i < d.omega.size(); ++i)
        os << "  \\omega_{" << i + 1 << "} &= " << tex(d.omega[i]) << " \\\\\n";
    for (std::size_t i = 0; i < d.direction.size(); ++i)
        os << "  n_{"
           << "xyz"[i] << "} &= " << tex(d.direction[i]) << " \\\\\n";
    os << "  T &= " << tex(d.kinetic) << " \\\\\n";
    os << "  V &= " << tex(d.potential) << " \\\\\n";
    os << "  L &= " << tex(d.lagrangian) << " \\\\\n";
    const std::size_t n = d.names.size();
    for (std::size_t i = 0; i < n; ++i)
        os << "  " << tex(d.p[i]) << " &= " << tex(d.momenta[i]) << " \\\\\n";
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i; j < n; ++j)
            os << "  M_{" << tex(d.q[i]) << tex(d.q[j]) << "} &= " << tex(d.mass_matrix[i][j])
               << " \\\\\n";
    for (std::size_t i = 0; i < n; ++i)
        os << "  0 &= " << tex(d.euler_lagrange[i]) << " \\\\\n";
    os << "  H &= " << tex(d.hamiltonian) << " \\\\\n";
    for (std::size_t i = 0; i < n; ++i)
        os << "  \\dot{" << tex(d.q[i]) << "} &= " << tex(d.qdot[i]) << " \\\\\n";
    for (std::size_t i = 0; i < n; ++i)
        os << "  \\dot{p}_{" << tex(d.q[i]) << "} &= " << tex(d.pdot[i]) << " \\\\\n";
    os << "  E &= " << tex(d.energy) << "\n";
    os << "\\end{align*}\n";
    if (!d.cyclic.empty()) {
        os << "% cyclic coordinates (momentum conserved):";
        for (int i : d.cyclic)
            os << " " << d.names[static_cast<std::size_t>(i)];
        os << "\n";
    }
    return os.str();
}

// The three-angle derivation as the printers take it.
equations top_equations(const derivation& d) {
    const auto& s = symbols();
    equations e = equations_of(d, 3, {s.q[0], s.q[1], s.q[2]}, {s.p[0], s.p[1], s.p[2]}, d.angles);
    e.omega.assign(d.omega.begin(), d.omega.end());
    const angle_convention& c = d.angles;
    if (c.is_default()) {
        e.coordinates_note = "phi, theta, psi (z-x-z Euler angles; singular at theta = 0, pi)";
        e.latex_note = "z-x-z Euler angles; singular at \\theta = 0, \\pi";
    } else {
        e.coordinates_note = c.names[0] + ", " + c.names[1] + ", " + c.names[2] + " (" +
                             c.description() + ", A = " + c.matrix_text() + "; singular at " +
                             c.singular_text() + ")";
        e.latex_note = c.description() + "; singular at " + c.singular_text();
    }
    return e;
}

} // namespace

std::string inspect_inertia(const model_spec& spec, output_format format, bool symbolic) {
    const inertia_report r = analyse_inertia(spec.inertia, spec.parameter_defaults());
    return format == output_format::latex ? inertia_latex(spec, r, symbolic)
                                          : inertia_text(spec, r, symbolic);
}

namespace {

std::string print(const model_spec& spec, const equations& e, output_format format,
                  bool with_inertia, bool symbolic) {
    if (with_inertia) {
        if (format != output_format::json) return inspect_inertia(spec, format, symbolic);
        const inertia_report r = analyse_inertia(spec.inertia, spec.parameter_defaults());
        return as_json(spec, e, &r);
    }
    switch (format) {
    case output_format::json:
        return as_json(spec, e, nullptr);
    case output_format::latex:
        return as_latex(spec, e);
    case output_format::text:
        break;
    }
    return as_text(spec, e);
}

} // namespace

std::string inspect(const model_spec& spec, const derivation& d, output_format format,
                    bool with_inertia, bool symbolic) {
    return print(spec, top_equations(d), format, with_inertia, symbolic);
}

std::string inspect_rotor(const model_spec& spec, output_format format, bool with_inertia,
                          bool symbolic) {
    return print(spec, rotor_equations(spec), format, with_inertia, symbolic);
}

} // namespace rotgen
