// rotgen bench: the struct variant_<i> the driver template receives for each variant.
#include "bench/numbers.hpp"
#include "bench/plan.hpp"
#include "bench/variants.hpp"
#include "expr/symbols.hpp"
#include "run/tolerance_layout.hpp"

#include <rotgen.hpp> // runtime: taylor<double>::order_for

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace rotgen::bench {

namespace {

// Its label, sizes and method bits; its run-time parameters, initial state and error layout.
void write_data(std::ostream& s, const variant& v, std::size_t index, const std::string& ns,
                const scene_spec& scene, const kinematics& k) {
    const std::size_t n = v.f.state.size();
    s << "struct variant_" << index << " {\n"
      << "    static constexpr const char* form = \"" << v.label << "\";\n"
      << "    static constexpr std::size_t state_size = " << ns << "::state_size;\n"
      << "    template <class T> using params = " << ns << "::params<T>;\n"
      << "    static constexpr unsigned double_methods = " << v.double_methods
      << ", float_methods = " << v.float_methods
      << ", long_double_methods = " << v.long_double_methods
      << ", drift_methods = " << v.drift_methods << ", peers = " << v.peers << ";\n";
    s << "    template <class T> static params<T> parameters() {\n        params<T> p;\n";
    for (const auto& p : v.f.parameters)
        if (!v.specialised || !p.specialisable)
            s << "        p." << p.name << " = T("
              << ld_literal(scene_parameter_value(scene, k, p.name)) << ");\n";
    s << "        return p;\n    }\n";
    s << "    static std::array<long double, " << n << "> initial() {\n        return {{";
    for (std::size_t i = 0; i < n; ++i)
        s << (i ? ", " : "") << ld_literal(state_value(k, v.f.angles, v.f.state[i].name));
    s << "}};\n    }\n";
    // what a tolerance is relative to, as `rotgen simulate` gives it to the form's methods
    s << "    static rotgen::error_layout layout() {\n        rotgen::error_layout l;\n"
      << "        l.groups = {";
    const error_layout layout = tolerance_layout(v.f.state, scene);
    for (std::size_t i = 0; i < layout.groups.size(); ++i)
        s << (i ? ", " : "") << int(layout.groups[i]);
    s << "};\n        l.span = " << ld_literal(layout.span) << ";\n        return l;\n    }\n";
}

// The Taylor variant's expansion: the orders of the plan's tolerances as straight-line code
// (taylor_fixed), as a run of the scene at one of them compiles its own.
std::string bench_taylor_call() {
    std::set<int> orders;
    for (double tol : taylor_tolerances())
        orders.insert(taylor<double>::order_for(tol));
    std::string call = "taylor_specialised<";
    for (int o : orders)
        call += (call.back() == '<' ? "" : ", ") + std::to_string(o);
    return call + ">";
}

// rhs and jacobian (the unlowered rhs from namespace <unit>_naive), energy, conserved momenta.
void write_functions(std::ostream& s, const variant& v, const std::string& ns,
                     const scene_spec& scene, const derivation& d) {
    const std::string rhs_ns = v.lowered ? ns : ns + "_naive";
    s << "    template <class T> static void rhs(T t, const T* y, T* dydt, const params<T>& p) {\n"
      << "        " << rhs_ns << "::rhs(t, y, dydt, p);\n    }\n"
      << "    template <class T> static void jacobian(T t, const T* y, T* J, const params<T>& p) "
         "{\n"
      << "        " << ns << "::jacobian(t, y, J, p);\n    }\n";
    if (std::find(v.outputs.begin(), v.outputs.end(), "taylor") != v.outputs.end())
        s << "    static constexpr std::size_t taylor_series = " << ns << "::taylor_series;\n"
          << "    template <class T> static void taylor(T t, T* c, int order, const params<T>& p) "
             "{\n"
          << "        " << ns << "::" << bench_taylor_call() << "(t, c, order, p);\n    }\n";
    s << "    static bool energy(const long double* y, long double* e) {\n";
    if (v.has_energy)
        s << "        *e = " << ns
          << "::energy(y, parameters<long double>());\n        return true;\n";
    else
        s << "        (void)y, (void)e;\n        return false;\n";
    s << "    }\n";
    // conserved momenta: the cyclic coordinates' (Euler-angle forms with a momenta output)
    s << "    static int momenta(const long double* y, long double* out) {\n";
    const bool momenta = v.form != form_kind::body && v.f.outputs.count("momenta") &&
                         !d.cyclic.empty() && !scene.model.has_damping && !scene.model.has_torque;
    if (momenta) {
        s << "        long double m[3];\n        " << ns
          << "::momenta(y, m, parameters<long double>());\n";
        for (std::size_t i = 0; i < d.cyclic.size(); ++i)
            s << "        out[" << i << "] = m[" << d.cyclic[i] << "];\n";
        s << "        return " << d.cyclic.size() << ";\n";
    } else {
        s << "        (void)y, (void)out;\n        return 0;\n";
    }
    s << "    }\n";
}

// The quantities of common_state.hpp, by the state or output name that holds them.
const std::map<std::string, std::string>& common_quantity() {
    static const std::map<std::string, std::string> q_of{
        {"omega1", "q_omega1"},   {"omega2", "q_omega2"},       {"omega3", "q_omega3"},
        {"phi", "q_phi"},         {"theta", "q_theta"},         {"psi", "q_psi"},
        {"phi_dot", "q_phi_dot"}, {"theta_dot", "q_theta_dot"}, {"psi_dot", "q_psi_dot"}};
    return q_of;
}

// c.set(q, array[i]) for each of `names` that is a common quantity (with `only_unset`, one not
// set yet).
void set_common(std::ostream& s, const std::vector<std::string>& names, const std::string& array,
                bool only_unset, std::set<std::string>& set) {
    const auto& q_of = common_quantity();
    for (std::size_t i = 0; i < names.size(); ++i)
        if (const auto it = q_of.find(names[i]);
            it != q_of.end() && !(only_unset && set.count(it->first))) {
            s << "        c.set(" << it->second << ", " << array << "[" << i << "]);\n";
            set.insert(it->first);
        }
}

// The common representation: from the state, then q_dot = dH/dp (the first rates of the
// Hamiltonian and reduced forms), the ignored rates, omega and the rotation A.
void write_common(std::ostream& s, const variant& v, const std::string& ns) {
    const std::size_t n = v.f.state.size();
    s << "    static void common(const long double* y, common_state& c) {\n"
      << "        const auto p = parameters<long double>();\n        (void)p;\n";
    std::set<std::string> set;
    std::vector<std::string> state_names;
    for (const auto& x : v.f.state)
        state_names.push_back(x.name);
    set_common(s, state_names, "y", false, set);
    if (v.form == form_kind::hamiltonian || v.form == form_kind::reduced) {
        s << "        long double d[" << n << "];\n        " << ns << "::rhs(0.0L, y, d, p);\n";
        set_common(s, v.f.rate_names, "d", true, set);
    }
    if (const auto o = v.f.outputs.find("ignored_rates"); o != v.f.outputs.end()) {
        s << "        long double r[" << o->second.values.size() << "];\n        " << ns
          << "::ignored_rates(y, r, p);\n";
        set_common(s, o->second.names, "r", false, set);
    }
    if (v.f.outputs.count("omega") && !set.count("omega1")) {
        s << "        long double w[3];\n        " << ns << "::omega(y, w, p);\n"
          << "        c.set(q_omega1, w[0]);\n        c.set(q_omega2, w[1]);\n"
          << "        c.set(q_omega3, w[2]);\n";
        set.insert("omega1");
    }
    if (v.has_A)
        s << "        long double a[9];\n        " << ns << "::rotation(y, a, p);\n"
          << "        c.set_rotation(a);\n";
    if (v.has_A && !set.count("theta")) s << "        c.angles_from_rotation();\n";
    if (v.has_A && !set.count("phi_dot") && set.count("omega1"))
        s << "        c.rates_from_omega();\n";
    s << "    }\n";
}

} // namespace

std::string variant_struct(const variant& v, std::size_t index, const scene_spec& scene,
                           const kinematics& k, const derivation& d) {
    const std::string ns = "rotgen::models::" + v.unit;
    std::ostringstream s;
    write_data(s, v, index, ns, scene, k);
    write_functions(s, v, ns, scene, d);
    write_common(s, v, ns); // the common representation (common_state.hpp)
    s << "};\n";
    return s.str();
}

} // namespace rotgen::bench
