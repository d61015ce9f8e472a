#include "inspect.hpp"

#include "print.hpp"
#include "symbols.hpp"

#include <sstream>

namespace rotgen {

using GiNaC::ex;

std::string json_quote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\t': out += "\\t"; break;
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

const std::array<std::string, 3>& names() { return coordinate_names(); }

std::string json_array(const vector3& v) {
    std::string s = "[";
    for (int i = 0; i < 3; ++i) s += (i ? ", " : "") + json_quote(to_text(v[i]));
    return s + "]";
}

std::string as_json(const model_spec& spec, const derivation& d) {
    std::ostringstream os;
    os << "{\n  \"model\": " << json_quote(spec.name) << ",\n  \"parameters\": {";
    for (std::size_t i = 0; i < spec.parameters.size(); ++i)
        os << (i ? ", " : "") << json_quote(spec.parameters[i].name) << ": "
           << format_double(spec.parameters[i].value);
    os << "},\n  \"coordinates\": [\"phi\", \"theta\", \"psi\"],\n";
    os << "  \"kinetic\": " << json_quote(to_text(d.kinetic)) << ",\n";
    os << "  \"potential\": " << json_quote(to_text(d.potential)) << ",\n";
    os << "  \"lagrangian\": " << json_quote(to_text(d.lagrangian)) << ",\n";
    os << "  \"momenta\": " << json_array(d.momenta) << ",\n";
    os << "  \"mass_matrix\": [";
    for (int i = 0; i < 3; ++i) os << (i ? ", " : "") << json_array(d.mass_matrix[i]);
    os << "],\n  \"euler_lagrange\": " << json_array(d.euler_lagrange) << ",\n";
    os << "  \"hamiltonian\": " << json_quote(to_text(d.hamiltonian)) << ",\n";
    os << "  \"hamilton_equations\": {\"qdot\": " << json_array(d.hamilton_qdot)
       << ", \"pdot\": " << json_array(d.hamilton_pdot) << "},\n";
    os << "  \"cyclic\": [";
    for (std::size_t i = 0; i < d.cyclic.size(); ++i)
        os << (i ? ", " : "") << json_quote(names()[d.cyclic[i]]);
    os << "],\n  \"energy\": " << json_quote(to_text(d.energy)) << "\n}\n";
    return os.str();
}

std::string as_text(const model_spec& spec, const derivation& d) {
    std::ostringstream os;
    os << "model " << spec.name << " (" << spec.file << ")\n";
    os << "coordinates: phi, theta, psi (z-x-z Euler angles; singular at theta = 0, pi)\n";
    os << "parameters:";
    if (spec.parameters.empty()) os << " none";
    for (const auto& p : spec.parameters) os << " " << p.name << " = " << format_double(p.value);
    os << "\n\nbody angular velocity (5.30):\n";
    for (int i = 0; i < 3; ++i) os << "  omega" << i + 1 << " = " << to_text(d.omega[i]) << "\n";
    os << "\nkinetic energy   T = " << to_text(d.kinetic) << "\n";
    os << "potential energy V = " << to_text(d.potential) << "\n";
    os << "Lagrangian       L = " << to_text(d.lagrangian) << "\n";
    os << "\ncanonical momenta p = dL/dq_dot:\n";
    for (int i = 0; i < 3; ++i) os << "  p_" << names()[i] << " = " << to_text(d.momenta[i]) << "\n";
    os << "\nmass matrix M(q) (symmetric; M q_ddot = f):\n";
    for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j)
            os << "  M[" << names()[i] << "][" << names()[j] << "] = " << to_text(d.mass_matrix[i][j])
               << "\n";
    os << "\nf(q, q_dot, t):\n";
    for (int i = 0; i < 3; ++i) os << "  f_" << names()[i] << " = " << to_text(d.forcing[i]) << "\n";
    os << "\nEuler-Lagrange equations (each = 0):\n";
    for (int i = 0; i < 3; ++i) os << "  " << to_text(d.euler_lagrange[i]) << " = 0\n";
    os << "\nHamiltonian H(q, p) = " << to_text(d.hamiltonian) << "\n";
    os << "\nHamilton's equations:\n";
    for (int i = 0; i < 3; ++i)
        os << "  " << names()[i] << "_dot = " << to_text(d.hamilton_qdot[i]) << "\n";
    for (int i = 0; i < 3; ++i)
        os << "  p_" << names()[i] << "_dot = " << to_text(d.hamilton_pdot[i]) << "\n";
    os << "\ncyclic coordinates:";
    if (d.cyclic.empty()) os << " none";
    for (int i : d.cyclic) os << " " << names()[i] << " (p_" << names()[i] << " conserved)";
    os << "\nenergy E = T + V = " << to_text(d.energy) << "\n";
    return os.str();
}

std::string as_latex(const model_spec& spec, const derivation& d) {
    const auto& s = symbols();
    std::ostringstream os;
    const auto tex = [](const ex& e) { return to_latex(e); };
    os << "% rotgen inspect --format latex: model " << spec.name << " (" << spec.file << ")\n";
    os << "% z-x-z Euler angles; singular at \\theta = 0, \\pi\n";
    os << "\\begin{align*}\n";
    for (int i = 0; i < 3; ++i)
        os << "  \\omega_{" << i + 1 << "} &= " << tex(d.omega[i]) << " \\\\\n";
    os << "  T &= " << tex(d.kinetic) << " \\\\\n";
    os << "  V &= " << tex(d.potential) << " \\\\\n";
    os << "  L &= " << tex(d.lagrangian) << " \\\\\n";
    for (int i = 0; i < 3; ++i) os << "  " << tex(s.p[i]) << " &= " << tex(d.momenta[i]) << " \\\\\n";
    for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j)
            os << "  M_{" << tex(s.q[i]) << tex(s.q[j]) << "} &= " << tex(d.mass_matrix[i][j])
               << " \\\\\n";
    for (int i = 0; i < 3; ++i) os << "  0 &= " << tex(d.euler_lagrange[i]) << " \\\\\n";
    os << "  H &= " << tex(d.hamiltonian) << " \\\\\n";
    for (int i = 0; i < 3; ++i)
        os << "  \\dot{" << tex(s.q[i]) << "} &= " << tex(d.hamilton_qdot[i]) << " \\\\\n";
    for (int i = 0; i < 3; ++i)
        os << "  \\dot{p}_{" << tex(s.q[i]) << "} &= " << tex(d.hamilton_pdot[i]) << " \\\\\n";
    os << "  E &= " << tex(d.energy) << "\n";
    os << "\\end{align*}\n";
    if (!d.cyclic.empty()) {
        os << "% cyclic coordinates (momentum conserved):";
        for (int i : d.cyclic) os << " " << names()[i];
        os << "\n";
    }
    return os.str();
}

} // namespace

std::string inspect(const model_spec& spec, const derivation& d, output_format format) {
    switch (format) {
    case output_format::json: return as_json(spec, d);
    case output_format::latex: return as_latex(spec, d);
    case output_format::text: break;
    }
    return as_text(spec, d);
}

} // namespace rotgen
