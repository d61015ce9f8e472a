// rotgen bench SCENE.yaml [-o DIR] [--quick] [--long-steps N]
//
// The speed-accuracy trade of one scene, measured (DESIGN.md "Measuring the speed-accuracy
// trade"): derive -> emit every variant of the scene's equations (formulation x code generation)
// -> fill bench/workprecision/driver.cpp.in -> compile it once (-O3, cached by a hash of the
// source, the harness, the runtime, the compiler and the flags) -> run the driver on a plan of
// configurations (integrator x tolerance or step x scalar type x variant, and the peers
// Boost.Odeint and SUNDIALS CVODE on the same kernels) -> results.csv, results.md,
// final_states.csv, drift.csv and the plots work_precision_time.png, work_precision_evals.png,
// invariant_drift.png in DIR (default bench-out/<scene>).
//
// Variants (the `form` column; every one specialised — parameters folded into the code — and
// lowered — CSE, hoisted trigonometry — unless its label says otherwise):
//   the scene's form                  main: every integrator, scalar type and peer
//   <main>+runtime                    parameters read from params<T> at run time
//   <main>+unlowered                  rhs printed expression by expression, no CSE (explicit
//                                     methods only; the emitter has no switch for this, so the
//                                     text comes from the printer here)
//   every other form that applies     lagrangian:explicit, lagrangian:solve, hamiltonian, reduced
//                                     (cyclic coordinates), body:quaternion, body:omega (free body)
// Angles are z-x-z Euler angles (5.3), A = Az(psi) Ax(theta) Az(phi) passive body <- space (5.25),
// omega in body axes (5.30).
#include "bench/bench.hpp"
#include "derive/derive.hpp"
#include "emit/emit.hpp"
#include "support/error.hpp"
#include "forms/forms.hpp"
#include "run/compile_cache.hpp"
#include "support/hash.hpp"
#include "support/process.hpp"
#include "expr/print.hpp"
#include "scene/scene.hpp"
#include "expr/symbols.hpp"

#include <rotation.hpp> // runtime: quaternion_from_euler

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace rotgen {

namespace {

namespace fs = std::filesystem;
using GiNaC::ex;

const char* const bench_usage = "rotgen bench SCENE.yaml [-o DIR] [--quick] [--long-steps N]";

struct bench_options {
    std::string scene, dir;
    bool quick = false;
    long long_steps = -1; // -1: 10^6 (10^4 with --quick); 0: no long run
};

user_error usage_error(const std::string& problem) {
    return user_error({"rotgen bench"}, problem);
}

bench_options parse_arguments(const std::vector<std::string>& args) {
    bench_options o;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "-o" || a == "--long-steps") {
            if (i + 1 >= args.size()) throw usage_error(a + " needs a value");
            const std::string v = args[++i];
            if (a == "-o") {
                o.dir = v;
            } else {
                char* end = nullptr;
                const long n = std::strtol(v.c_str(), &end, 10);
                if (!end || *end || n < 0 || n > 100000000)
                    throw usage_error(
                        "--long-steps needs a whole number of steps in [0, 1e8], got '" + v + "'");
                o.long_steps = n;
            }
        } else if (a == "--quick") {
            o.quick = true;
        } else if (!a.empty() && a[0] == '-') {
            const std::string best = closest_name(a, {"-o", "--quick", "--long-steps"});
            throw usage_error("unknown option '" + a + "' for bench" +
                              (best.empty() ? "" : "; did you mean '" + best + "'?"));
        } else if (o.scene.empty()) {
            o.scene = a;
        } else {
            throw usage_error("bench takes one scene file, got '" + o.scene + "' and '" + a + "'");
        }
    }
    if (o.scene.empty()) throw usage_error(std::string("bench needs a scene file: ") + bench_usage);
    if (o.long_steps < 0) o.long_steps = o.quick ? 10000 : 1000000;
    if (o.dir.empty()) o.dir = "bench-out/" + fs::path(o.scene).stem().string();
    return o;
}

// ---- where the harness and the runtime are ---------------------------------------------------

// Where the harness (bench/workprecision) and the runtime headers are: $ROTGEN_SOURCE_DIR (a
// source tree) when set; else the installed layout next to this executable
// (<prefix>/share/rotgen/bench/workprecision and <prefix>/include/rotgen/runtime); the source tree
// this file was compiled from (a build tree).
struct bench_sources {
    fs::path harness, runtime;
};

bench_sources find_bench_sources() {
    const auto complete = [](const bench_sources& c) {
        std::error_code ec;
        return fs::exists(c.harness / "harness.hpp", ec) && fs::exists(c.runtime / "rotgen.hpp", ec);
    };
    if (const char* d = std::getenv("ROTGEN_SOURCE_DIR"); d && *d) {
        // asked for explicitly: that tree or an error, never a silent fallback
        const bench_sources c{fs::path(d) / "bench/workprecision", fs::path(d) / "runtime"};
        if (!complete(c))
            throw user_error({"ROTGEN_SOURCE_DIR=" + std::string(d)},
                             "not a rotgen source tree (no bench/workprecision/harness.hpp and "
                             "runtime/rotgen.hpp there)");
        return c;
    }
    std::vector<bench_sources> candidates;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path prefix = exe.parent_path().parent_path();
        candidates.push_back(
            {prefix / "share/rotgen/bench/workprecision", prefix / "include/rotgen/runtime"});
    }
    const fs::path tree = ROTGEN_SOURCE_TREE; // set by generator/CMakeLists.txt
    candidates.push_back({tree / "bench/workprecision", tree / "runtime"});
    std::string looked;
    for (const auto& c : candidates) {
        if (complete(c)) return c;
        looked += (looked.empty() ? "" : ", ") + c.harness.string();
    }
    throw user_error({"rotgen bench"}, "cannot find the harness (bench/workprecision/harness.hpp) "
                                       "and the runtime headers; looked in " +
                                           looked +
                                           "; set ROTGEN_SOURCE_DIR to the rotgen source tree");
}

std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + p.string());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string eigen_flags() {
    int status = 0;
    std::string f = run_capture("pkg-config --cflags eigen3", &status);
    if (status != 0 || f.find("-I") == std::string::npos) f = "-I/usr/include/eigen3";
    while (!f.empty() && (f.back() == '\n' || f.back() == ' '))
        f.pop_back();
    return f;
}

// ---- numbers -----------------------------------------------------------------------------------

std::string ld_literal(long double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.21LgL", x);
    std::string s = buf;
    if (s.find_first_of(".eEn") == std::string::npos) s.insert(s.size() - 1, ".0");
    return s;
}

std::string ld_plain(long double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.21Lg", x);
    return buf;
}

std::string plain(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

std::string short_number(double x, int digits = 3) {
    if (std::isnan(x)) return "";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    return buf;
}

// GiNaC value -> long double, through its decimal text (Digits = 30).
long double to_long_double(const ex& e) {
    const ex v = GiNaC::evalf(e);
    if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
        throw std::logic_error("bench: expression did not evaluate to a real number");
    std::ostringstream os;
    os << v;
    return std::stold(os.str());
}

// ---- the initial state in every coordinate, in long double ------------------------------------

struct kinematics {
    std::array<long double, 3> q{}, qd{}, p{}, omega{};
    bool have_rates = true;
    Eigen::Quaternion<long double> quat;
};

kinematics initial_kinematics(const scene_spec& scene, const derivation& d,
                              const GiNaC::exmap& parameters) {
    const auto& s = symbols();
    const long saved = GiNaC::Digits;
    GiNaC::Digits = 30;
    kinematics k;
    try {
        GiNaC::exmap at = parameters;
        for (int i = 0; i < 3; ++i) {
            at[s.q[i]] = exact_decimal(scene.angles[i]);
            k.q[i] = to_long_double(exact_decimal(scene.angles[i]));
        }
        std::array<ex, 3> qd;
        const bool singular = std::abs(std::sin(scene.angles[1])) < 1e-12;
        switch (scene.initial) {
        case initial_kind::rates:
            for (int i = 0; i < 3; ++i)
                qd[i] = exact_decimal(scene.initial_rates[i]);
            break;
        case initial_kind::momenta: {
            if (singular) {
                k.have_rates = false;
                break;
            }
            // M q_dot = p, solved in long double
            Eigen::Matrix<long double, 3, 3> M;
            Eigen::Matrix<long double, 3, 1> p;
            for (int i = 0; i < 3; ++i) {
                p[i] = to_long_double(exact_decimal(scene.initial_rates[i]));
                for (int j = 0; j < 3; ++j)
                    M(i, j) = to_long_double(d.mass_matrix[i][j].subs(at));
            }
            const Eigen::Matrix<long double, 3, 1> v = M.fullPivLu().solve(p);
            for (int i = 0; i < 3; ++i) {
                char buf[64];
                std::snprintf(buf, sizeof buf, "%.21Le", v[i]);
                qd[i] = GiNaC::numeric(buf);
            }
            break;
        }
        case initial_kind::omega:
            if (singular) {
                k.have_rates = false;
                break;
            }
            for (int i = 0; i < 3; ++i) {
                ex r = 0;
                for (int j = 0; j < 3; ++j)
                    r += d.inverse_omega_jacobian[i][j] * exact_decimal(scene.initial_rates[j]);
                qd[i] = r.subs(at);
            }
            break;
        }
        if (k.have_rates) {
            for (int i = 0; i < 3; ++i)
                at[s.qd[i]] = qd[i];
            for (int i = 0; i < 3; ++i) {
                k.qd[i] = to_long_double(qd[i]);
                k.p[i] = to_long_double(d.momenta[i].subs(at));
                k.omega[i] = to_long_double(d.omega[i].subs(at));
            }
        }
        if (scene.initial == initial_kind::omega)
            for (int i = 0; i < 3; ++i)
                k.omega[i] = to_long_double(exact_decimal(scene.initial_rates[i]));
    } catch (...) {
        GiNaC::Digits = saved;
        throw;
    }
    GiNaC::Digits = saved;
    k.quat = quaternion_from_euler<long double>(k.q[0], k.q[1], k.q[2]);
    return k;
}

// The runs are in double (and float): initial values whose rates, momenta or kinetic energy
// (1/2 p . q_dot) overflow double are refused up front, as `simulate` does, rather than reported as
// a sweep of non-finite runs.
void check_double_range(const scene_spec& scene, const kinematics& k) {
    const long double big = std::numeric_limits<double>::max();
    const auto check = [&](const std::string& what, long double v) {
        if (std::isfinite(v) && std::abs(v) <= big) return;
        throw user_error(scene.initial_where,
                         "initial values too large for double precision: " + what + " = " +
                             std::to_string(static_cast<double>(v)) +
                             "; give smaller initial rates or momenta, or rescale the model's units");
    };
    const std::array<const char*, 3> q{"phi", "theta", "psi"};
    long double twice_kinetic = 0;
    for (std::size_t i = 0; i < 3; ++i) {
        check("omega" + std::to_string(i + 1), k.omega[i]);
        if (!k.have_rates) continue;
        check(std::string(q[i]) + "_dot", k.qd[i]);
        check(std::string("p_") + q[i], k.p[i]);
        twice_kinetic += k.p[i] * k.qd[i];
    }
    check("the kinetic energy", twice_kinetic / 2);
}

// ---- the variants -------------------------------------------------------------------------------

enum class role { main, runtime, unlowered, alternative };

struct variant {
    std::string unit, label;
    form_kind form = form_kind::lagrangian;
    lagrangian_strategy strategy = lagrangian_strategy::explicit_inverse;
    bool quaternion = false; // body form: keep the orientation
    bool specialised = true, lowered = true;
    role r = role::alternative;
    bool implicit_runs = false; // the plan runs its implicit methods too
    unsigned double_methods = 0, float_methods = 0, long_double_methods = 0, drift_methods = 0,
             peers = 0; // what the driver compiles for it (bits of harness.hpp)
    form_expressions f;
    std::vector<std::string> outputs;
    emitted_header header;
    std::string naive; // the unlowered rhs (namespace <unit>_naive)
    bool has_A = false, has_energy = false;
};

std::string form_label(form_kind form, lagrangian_strategy strategy, bool quaternion) {
    switch (form) {
    case form_kind::lagrangian:
        return strategy == lagrangian_strategy::solve ? "lagrangian:solve" : "lagrangian:explicit";
    case form_kind::hamiltonian:
        return "hamiltonian";
    case form_kind::reduced:
        return "reduced";
    case form_kind::body:
        return quaternion ? "body:quaternion" : "body:omega";
    }
    return "";
}

// The unlowered rhs: every rate printed on its own by the C printer (no CSE, no hoisting).
std::string naive_rhs(const variant& v, const GiNaC::exmap& folded) {
    std::map<std::string, std::string> names;
    for (std::size_t i = 0; i < v.f.state.size(); ++i)
        names[v.f.state[i].name] = "y[" + std::to_string(i) + "]";
    for (const auto& p : v.f.parameters)
        names[p.name] = "p." + p.name;
    names["t"] = "t";
    const c_printer print(names, "T");
    std::ostringstream os;
    os << "namespace rotgen {\nnamespace models {\nnamespace " << v.unit << "_naive {\n"
       << "// The rates printed expression by expression: no common subexpressions shared, no\n"
       << "// trigonometry hoisted (the `+unlowered` variant of the work-precision bench).\n"
       << "template <class T>\nvoid rhs(T t, const T* y, T* dydt, const " << v.unit
       << "::params<T>& p) {\n"
       << "    using std::sin; using std::cos; using std::tan; using std::sqrt; using std::pow;\n"
       << "    using std::exp; using std::log; using std::abs; using std::atan2;\n"
       << "    (void)t; (void)y; (void)p;\n";
    for (std::size_t i = 0; i < v.f.rates.size(); ++i)
        os << "    dydt[" << i << "] = " << print(v.f.rates[i].subs(folded)) << ";\n";
    os << "}\n} // namespace " << v.unit
       << "_naive\n} // namespace models\n} // namespace rotgen\n";
    return os.str();
}

// Value of a run-time parameter of a variant: the scene's, or a conserved momentum.
long double parameter_value(const std::string& name, const scene_spec& scene, const kinematics& k) {
    const model_spec& spec = scene.model;
    for (std::size_t i = 0; i < spec.parameters.size(); ++i)
        if (spec.parameters[i].name == name) {
            const long saved = GiNaC::Digits;
            GiNaC::Digits = 30;
            const long double v = to_long_double(exact_decimal(scene.parameters[i]));
            GiNaC::Digits = saved;
            return v;
        }
    for (int i = 0; i < 3; ++i)
        if (name == "p_" + coordinate_names()[i]) return k.p[static_cast<std::size_t>(i)];
    throw std::logic_error("bench: no value for parameter " + name);
}

long double state_value(const std::string& name, const kinematics& k) {
    for (int i = 0; i < 3; ++i) {
        const std::string& q = coordinate_names()[i];
        const auto u = static_cast<std::size_t>(i);
        if (name == q) return k.q[u];
        if (name == q + "_dot") return k.qd[u];
        if (name == "p_" + q) return k.p[u];
        if (name == "omega" + std::to_string(i + 1)) return k.omega[u];
    }
    if (name == "qw") return k.quat.w();
    if (name == "qx") return k.quat.x();
    if (name == "qy") return k.quat.y();
    if (name == "qz") return k.quat.z();
    throw std::logic_error("bench: unknown state variable " + name);
}

// The variant struct the driver template receives.
std::string variant_struct(const variant& v, std::size_t index, const scene_spec& scene,
                           const kinematics& k, const derivation& d) {
    const std::string ns = "rotgen::models::" + v.unit;
    const std::string rhs_ns = v.lowered ? ns : ns + "_naive";
    const std::size_t n = v.f.state.size();
    std::ostringstream s;
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
            s << "        p." << p.name << " = T(" << ld_literal(parameter_value(p.name, scene, k))
              << ");\n";
    s << "        return p;\n    }\n";
    s << "    static std::array<long double, " << n << "> initial() {\n        return {{";
    for (std::size_t i = 0; i < n; ++i)
        s << (i ? ", " : "") << ld_literal(state_value(v.f.state[i].name, k));
    s << "}};\n    }\n";
    s << "    template <class T> static void rhs(T t, const T* y, T* dydt, const params<T>& p) {\n"
      << "        " << rhs_ns << "::rhs(t, y, dydt, p);\n    }\n"
      << "    template <class T> static void jacobian(T t, const T* y, T* J, const params<T>& p) "
         "{\n"
      << "        " << ns << "::jacobian(t, y, J, p);\n    }\n";
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
    // the common representation (common_state.hpp)
    s << "    static void common(const long double* y, common_state& c) {\n"
      << "        const auto p = parameters<long double>();\n        (void)p;\n";
    static const std::map<std::string, std::string> q_of{
        {"omega1", "q_omega1"},   {"omega2", "q_omega2"},       {"omega3", "q_omega3"},
        {"phi", "q_phi"},         {"theta", "q_theta"},         {"psi", "q_psi"},
        {"phi_dot", "q_phi_dot"}, {"theta_dot", "q_theta_dot"}, {"psi_dot", "q_psi_dot"}};
    std::set<std::string> set;
    for (std::size_t i = 0; i < n; ++i)
        if (const auto it = q_of.find(v.f.state[i].name); it != q_of.end()) {
            s << "        c.set(" << it->second << ", y[" << i << "]);\n";
            set.insert(v.f.state[i].name);
        }
    if (v.form == form_kind::hamiltonian || v.form == form_kind::reduced) {
        // q_dot = dH/dp: the first rates of the state
        s << "        long double d[" << n << "];\n        " << ns << "::rhs(0.0L, y, d, p);\n";
        for (std::size_t i = 0; i < v.f.rate_names.size(); ++i)
            if (const auto it = q_of.find(v.f.rate_names[i]);
                it != q_of.end() && !set.count(it->first)) {
                s << "        c.set(" << it->second << ", d[" << i << "]);\n";
                set.insert(it->first);
            }
    }
    if (const auto o = v.f.outputs.find("ignored_rates"); o != v.f.outputs.end()) {
        s << "        long double r[" << o->second.values.size() << "];\n        " << ns
          << "::ignored_rates(y, r, p);\n";
        for (std::size_t i = 0; i < o->second.names.size(); ++i)
            if (const auto it = q_of.find(o->second.names[i]); it != q_of.end()) {
                s << "        c.set(" << it->second << ", r[" << i << "]);\n";
                set.insert(it->first);
            }
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
    s << "    }\n};\n";
    return s.str();
}

// ---- the plan
// ------------------------------------------------------------------------------------

// The method bits of bench/workprecision/harness.hpp (method_bit, odeint_method, cvode_bit).
unsigned method_bit(const std::string& method) {
    if (method == "rk4") return 1;
    if (method == "dopri5") return 2;
    if (method == "dop853") return 4;
    if (method == "implicit_midpoint") return 8;
    if (method == "rodas4") return 16;
    throw std::logic_error("bench: unknown method " + method);
}
unsigned peer_bit(const std::string& peer, const std::string& method) {
    if (peer == "cvode") return 8;
    return method == "dopri5" ? 1 : method == "rkf78" ? 2 : 4;
}

// The plan's text, and what each variant must compile for it.
struct plan_builder {
    std::ostringstream text;
    std::vector<variant>* variants = nullptr;
    void run(std::size_t v, const std::string& peer, const std::string& method,
             const std::string& scalar, double tol, double step) {
        text << "run " << v << " " << peer << " " << method << " " << scalar << " " << plain(tol)
             << " " << plain(step) << "\n";
        variant& x = (*variants)[v];
        if (peer != "rotgen")
            x.peers |= peer_bit(peer, method);
        else
            (scalar == "float"         ? x.float_methods
             : scalar == "long_double" ? x.long_double_methods
                                       : x.double_methods) |= method_bit(method);
        ++lines;
    }
    std::size_t lines = 0;
};

// ---- reading the driver's output -----------------------------------------------------------

struct result_row {
    std::size_t variant = 0;
    std::string peer, method, form, scalar, status;
    double tol = 0, step = 0, error = NAN, orientation = NAN;
    std::size_t rhs = 0, jac = 0, steps = 0;
    double median = NAN, min = NAN, max = NAN, energy_drift = NAN, momentum_drift = NAN;
    std::vector<std::string> y;
    bool ok() const { return status == "ok" && std::isfinite(error); }
};

struct drift_point {
    std::string label;
    double t, e;
    std::size_t steps, rhs;
};

double parse_number(const std::string& s) {
    if (s == "nan" || s == "-nan") return NAN;
    return std::strtod(s.c_str(), nullptr);
}

// ---- output files ------------------------------------------------------------------------------

// Written to a temporary beside the target, then renamed: never a partial file.
void write_file(const fs::path& path, const std::string& text) {
    const fs::path tmp = path.string() + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        if (!out) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw user_error({path.string()}, std::string("cannot write: ") + std::strerror(errno));
        }
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) throw user_error({path.string()}, "cannot write: " + ec.message());
}

std::string csv_number(double x) {
    return std::isfinite(x) ? short_number(x, 6) : "";
}

// The method of a configuration as the tables and plots name it: an adaptive method run with a
// fixed step (rotgen's DOP853, Odeint's Fehlberg 7(8)) is a curve of its own, "dop853 fixed".
std::string method_key(const result_row& r) {
    const bool adaptive = r.method == "dop853" || r.method == "dopri5" || r.method == "rkf78";
    return adaptive && r.step > 0 ? r.method + " fixed" : r.method;
}

std::string method_title(const result_row& r) {
    return r.peer == "rotgen" ? method_key(r) : r.peer + " " + method_key(r);
}

// "1e-09" -> "1e-9"
std::string tol_text(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0e", x);
    std::string s = buf;
    const auto e = s.find("e-0");
    if (e != std::string::npos) s.erase(e + 2, 1);
    const auto p = s.find("e+0");
    if (p != std::string::npos) s.erase(p + 1, 2);
    return s;
}

// One curve of a plot: the points of one configuration (method, peer, form, scalar).
struct curve {
    std::string key, title, panel;
    int color = 0, dash = 1, point = 1;
    std::vector<const result_row*> points;
};

std::string gnuplot_escape(std::string s) {
    std::string r;
    for (char c : s)
        r += c == '\'' ? std::string("''") : std::string(1, c);
    return r;
}

void run_gnuplot(const fs::path& script_path, const std::string& script, const fs::path& png) {
    write_file(script_path, script);
    int status = 0;
    const std::string log = run_capture("gnuplot " + shell_quote(script_path.string()), &status);
    if (status != 0)
        throw user_error({png.string()}, "gnuplot failed to draw the plot (is gnuplot-nox "
                                         "installed?): " +
                                             log.substr(0, 400));
}

// The name of a configuration, for the tables.
std::string config_name(const result_row* r) {
    if (!r) return std::string("—");
    std::string s = (r->peer == "rotgen" ? "rotgen " : r->peer + " ") + r->method + " " +
                    r->scalar + " " + r->form;
    s += r->tol > 0 ? " tol " + tol_text(r->tol) : " h " + short_number(r->step, 3);
    return s;
}

// The fastest configuration at or below an error level: a measured point, per kind of peer.
struct best_entry {
    const result_row* rotgen = nullptr;
    const result_row* peer = nullptr;
};

// The time (and RHS evaluations) a configuration's curve needs to reach an error level.
struct reach {
    std::string curve;
    double time = NAN, rhs = NAN;
    bool peer = false;
};

// The fewest RHS evaluations of a method (double, main form) at or below an error level.
const result_row* fewest(const std::vector<result_row>& rows, const std::string& peer,
                         const std::string& method, double level) {
    const result_row* b = nullptr;
    for (const auto& r : rows)
        if (r.ok() && r.peer == peer && method_key(r) == method && r.scalar == "double" &&
            r.variant == 0 && r.error <= level && (!b || r.rhs < b->rhs))
            b = &r;
    return b;
}

// One `rotgen bench` run: its state, and the stages (member functions, in the order run() calls
// them) that fill it.
struct bench_run {
    using clock = std::chrono::steady_clock;

    int run(const std::vector<std::string>& args) {
        this->args = args;
        prepare();             // options, scene, output directory
        choose_variants();     // derive; the forms and code-generation variants
        make_plan();           // the configurations, the reference, the long runs -> plan.txt
        write_driver_source(); // emit every variant into driver.cpp.in
        compile_driver();      // once per source, cached
        run_driver();          // plan.txt -> raw.txt
        read_output();
        write_tables(); // results.csv, final_states.csv, drift.csv
        summarise();    // the best configuration per accuracy
        write_markdown();
        draw_plots();
        finish(); // results.md, the summary on stdout
        return 0;
    }

    void prepare();
    void choose_variants();
    void make_plan();
    void write_driver_source();
    void compile_driver();
    void run_driver();
    void read_output();
    void write_tables();
    void summarise();
    void write_markdown();
    void draw_plots();
    void finish();

    std::vector<std::string> args;
    clock::time_point wall0, t_gen;
    bench_options opt;
    scene_spec scene;
    model_spec spec; // the scene's model, with the scene's parameter values
    bench_sources src;
    fs::path dir;
    bool euler_ok = true, orientation = false, conservative = true;
    derivation d;
    GiNaC::exmap parameter_values;
    kinematics k0;
    std::string scene_name;
    std::vector<variant> variants;
    std::optional<std::size_t> hamiltonian_variant;
    // the plan
    double t0 = 0, t1 = 0, nu = 1, target = 0.02;
    const int repeats = 7; // timed loops per configuration (>= 5)
    plan_builder plan;
    std::size_t ref_variant = 0;
    std::vector<std::string> drift_labels;
    // the driver
    std::string source;
    // With GCC, an inlining limit high enough that every integrator — Odeint's header-only steppers
    // as much as rotgen's — is inlined into its loop as it would be in a program that uses it once:
    // at GCC's default, one translation unit holding many configurations outlines Odeint's
    // Fehlberg 7(8) step (13.8 against 9.0 us for 119 fixed steps of the free top, 39 against
    // 28 us adaptive), which measured the inliner's budget, not the integrator. (set in compile)
    std::string flags = "-std=c++17 -O3 -fno-math-errno -DNDEBUG";
    fs::path cache, exe, raw;
    bool cached = false;
    double generate_seconds = 0, compile_seconds = 0, run_seconds = 0, wall_seconds = 0;
    std::string load_before, load_after;
    // its results
    std::vector<result_row> rows;
    std::vector<drift_point> drift_points;
    std::map<std::string, std::string> drift_failed;
    std::string compared, reference_source;
    double reference_error = NAN, reference_orientation = NAN;
    std::vector<std::string> reference_runs;
    std::vector<double> levels;
    std::vector<best_entry> best;
    std::vector<std::pair<reach, reach>> reached; // (rotgen, peer) per level
    std::string markdown;
};

void bench_run::prepare() {
    wall0 = clock::now();
    opt = parse_arguments(args);
    scene = load_scene(opt.scene);
    spec = scene.model; // with the scene's parameter values
    for (std::size_t i = 0; i < spec.parameters.size(); ++i)
        spec.parameters[i].value = scene.parameters[i];
    src = find_bench_sources();
    dir = opt.dir;
    {
        std::error_code ec;
        if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
            throw user_error({dir.string()}, "the output path exists and is not a directory");
        fs::create_directories(dir, ec);
        if (ec)
            throw user_error({dir.string()}, "cannot create the output directory: " + ec.message());
        const fs::path probe = dir / (".probe" + std::to_string(::getpid()));
        std::ofstream p(probe);
        if (!p)
            throw user_error({dir.string()}, std::string("cannot write: ") + std::strerror(errno));
        p.close();
        fs::remove(probe, ec);
    }
    euler_ok = std::abs(std::sin(scene.angles[1])) > 1e-10;
    if (!euler_ok && scene.form != form_kind::body)
        throw user_error(scene.initial_where, "initial theta is the gimbal-lock singularity of the "
                                              "Euler-angle forms (sin theta = 0); use form: body");
}

void bench_run::choose_variants() {
    t_gen = clock::now();
    d = derive(spec);
    for (std::size_t i = 0; i < spec.parameters.size(); ++i)
        parameter_values[spec.parameters[i].symbol] = exact_decimal(scene.parameters[i]);
    k0 = initial_kinematics(scene, d, parameter_values);
    check_double_range(scene, k0);

    orientation = false; // as `simulate`: the body form keeps the quaternion if recorded
    for (const auto& name : scene.record)
        orientation = orientation || name == "phi" || name == "theta" || name == "psi" ||
                      name.rfind("body_", 0) == 0;
    conservative = !spec.has_damping && !spec.has_torque;
    scene_name = fs::path(opt.scene).stem().string();

    const auto add = [&](form_kind form, lagrangian_strategy strategy, bool quaternion, role r,
                         bool specialised, bool lowered) -> bool {
        variant v;
        v.form = form;
        v.strategy = strategy;
        v.r = r;
        v.specialised = specialised;
        v.lowered = lowered;
        try {
            v.f = build_form(spec, d, form, strategy, quaternion);
        } catch (const user_error&) {
            return false; // no such form for this model (e.g. reduced without cyclic coordinates)
        }
        v.quaternion = form == form_kind::body && v.f.state.size() == 7;
        if (form == form_kind::body && quaternion != v.quaternion) return false;
        if (form != form_kind::body && !(euler_ok && k0.have_rates)) return false;
        v.label = form_label(form, strategy, v.quaternion) + (specialised ? "" : "+runtime") +
                  (lowered ? "" : "+unlowered");
        for (const auto& existing : variants)
            if (existing.label == v.label) return false;
        v.unit = "wp" + std::to_string(variants.size()) + "_" + spec.name;
        v.outputs = {"rhs", "jacobian"};
        for (const char* o : {"energy", "momenta", "omega", "rotation", "ignored_rates"})
            if (v.f.outputs.count(o)) v.outputs.push_back(o);
        v.has_A = v.f.outputs.count("rotation") > 0;
        v.has_energy = v.f.outputs.count("energy") > 0;
        variants.push_back(std::move(v));
        return true;
    };
    // the main variant: the scene's form, as `simulate` runs it
    if (!add(scene.form, lagrangian_strategy::explicit_inverse, orientation, role::main, true,
             true))
        if (!add(scene.form, lagrangian_strategy::explicit_inverse, true, role::main, true, true))
            throw user_error(scene.where, "the scene's form cannot be benchmarked");
    variants[0].implicit_runs = true;
    const form_kind main_form = variants[0].form;
    const bool main_quat = variants[0].quaternion;
    add(main_form, lagrangian_strategy::explicit_inverse, main_quat, role::runtime, false, true);
    add(main_form, lagrangian_strategy::explicit_inverse, main_quat, role::unlowered, true, false);
    // the other forms
    struct alt {
        form_kind form;
        lagrangian_strategy strategy;
        bool quaternion;
    };
    std::vector<alt> alts = {{form_kind::lagrangian, lagrangian_strategy::explicit_inverse, false},
                             {form_kind::lagrangian, lagrangian_strategy::solve, false},
                             {form_kind::hamiltonian, lagrangian_strategy::explicit_inverse, false},
                             {form_kind::reduced, lagrangian_strategy::explicit_inverse, false},
                             {form_kind::body, lagrangian_strategy::explicit_inverse, true},
                             {form_kind::body, lagrangian_strategy::explicit_inverse, false}};
    if (opt.quick) alts.resize(1);
    for (const auto& a : alts)
        if (add(a.form, a.strategy, a.quaternion, role::alternative, true, true))
            variants.back().implicit_runs = true;
    // the unlowered variant is dropped when its text would be unreasonably long
    for (auto& v : variants) {
        if (v.lowered) continue;
        GiNaC::exmap folded;
        for (const auto& p : v.f.parameters)
            if (p.specialisable) folded[p.symbol] = exact_decimal(p.value);
        v.naive = naive_rhs(v, folded);
    }
    variants.erase(
        std::remove_if(variants.begin(), variants.end(),
                       [](const variant& v) { return !v.lowered && v.naive.size() > 400000; }),
        variants.end());
    // the long runs: the Hamiltonian form (canonical: the midpoint rule is symplectic there)
    for (std::size_t i = 0; i < variants.size(); ++i)
        if (variants[i].form == form_kind::hamiltonian && variants[i].r != role::runtime &&
            variants[i].lowered)
            hamiltonian_variant = i;
}

void bench_run::make_plan() {
    t0 = scene.t_start;
    t1 = scene.t_end;
    const double span = t1 - t0;
    nu = 0; // the fastest rate of the motion, for the fixed steps
    for (int i = 0; i < 3; ++i) {
        nu += double(k0.omega[static_cast<std::size_t>(i)] * k0.omega[static_cast<std::size_t>(i)]);
    }
    nu = std::sqrt(nu);
    if (k0.have_rates)
        for (int i = 0; i < 3; ++i)
            nu = std::max(nu, double(std::abs(k0.qd[static_cast<std::size_t>(i)])));
    nu = std::max(nu, 1e-3);
    // steps h = c / nu, snapped to span / N
    const auto steps_for = [&](const std::vector<double>& cs) {
        std::vector<double> hs;
        for (double c : cs) {
            const double n = std::ceil(span / (c / nu));
            if (n < 10 || n > 2e6) continue;
            hs.push_back(span / n);
        }
        return hs;
    };
    std::vector<double> tols_all = {1e-3, 1e-4,  1e-5,  1e-6,  1e-7, 1e-8,
                                    1e-9, 1e-10, 1e-11, 1e-12, 1e-13};
    std::vector<double> tols_odd = {1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-13};
    std::vector<double> tols_rodas = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
    std::vector<double> tols_bdf = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
    std::vector<double> tols_float = {1e-3, 1e-4, 1e-5};
    std::vector<double> tols_long = {1e-3,  1e-4,  1e-5,  1e-6,  1e-7,  1e-8, 1e-9,
                                     1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15};
    std::vector<double> rk4_steps = steps_for({0.3, 0.1, 0.03, 0.01, 0.003, 0.001, 0.0003});
    std::vector<double> rk4_alt = steps_for({0.1, 0.01, 0.001});
    std::vector<double> mid_steps = steps_for({0.3, 0.1, 0.03, 0.01, 0.003});
    std::vector<double> mid_alt = steps_for({0.1, 0.01});
    // DOP853 (and Odeint's Fehlberg 7(8)) with fixed steps: what error control costs
    std::vector<double> high_steps = steps_for({1.5, 1, 0.7, 0.5, 0.35, 0.25, 0.18, 0.12});
    target = 0.02; // seconds per timed loop
    if (opt.quick) {
        tols_all = {1e-5, 1e-8};
        tols_odd = {1e-8};
        tols_rodas = {1e-5};
        tols_bdf = {1e-6};
        tols_float = {1e-4};
        tols_long = {1e-12};
        rk4_steps = mid_steps = steps_for({0.03});
        high_steps = steps_for({0.5});
        rk4_alt.clear();
        mid_alt.clear();
        target = 0.002;
    }
    plan.variants = &variants;
    plan.text << "span " << plain(t0) << " " << plain(t1) << "\n"
              << "timing " << plain(target) << " " << repeats << "\n"
              << "autonomous " << (spec.has_torque ? 0 : 1) << "\n";
    // the reference
    bool principal_free =
        conservative && spec.inertia_diagonal && spec.potential.is_zero() && !spec.gravity;
    std::array<long double, 3> moments{};
    if (principal_free) {
        const long saved = GiNaC::Digits;
        GiNaC::Digits = 30;
        for (int i = 0; i < 3; ++i) {
            const ex m = spec.inertia[i][i].subs(parameter_values);
            moments[static_cast<std::size_t>(i)] = to_long_double(m);
            principal_free = principal_free && moments[static_cast<std::size_t>(i)] > 0;
        }
        GiNaC::Digits = saved;
    }
    ref_variant = 0;
    for (std::size_t i = 0; i < variants.size(); ++i)
        if (variants[i].has_A && variants[i].lowered) {
            ref_variant = i;
            break;
        }
    variants[ref_variant].long_double_methods |= method_bit("dop853");
    if (principal_free) {
        plan.text << "exact";
        for (long double x : {moments[0], moments[1], moments[2], k0.omega[0], k0.omega[1],
                              k0.omega[2], k0.q[0], k0.q[1], k0.q[2]})
            plan.text << " " << ld_plain(x);
        plan.text << "\n";
    }
    plan.text << "reference " << ref_variant << " 2e-18 2e-16\n";
    // the configurations
    for (std::size_t i = 0; i < variants.size(); ++i) {
        const variant& v = variants[i];
        const bool is_main = v.r == role::main;
        const bool explicit_only = v.r == role::runtime || v.r == role::unlowered;
        const auto& tols = is_main || explicit_only ? tols_all : tols_odd;
        for (double h : is_main || explicit_only ? rk4_steps : rk4_alt)
            plan.run(i, "rotgen", "rk4", "double", 0, h);
        if (is_main || (explicit_only && !opt.quick)) // (other forms: dop853, rk4, midpoint)
            for (double tol : tols)
                plan.run(i, "rotgen", "dopri5", "double", tol, 0);
        for (double tol : tols)
            plan.run(i, "rotgen", "dop853", "double", tol, 0);
        if (!explicit_only && v.implicit_runs) {
            for (double h : is_main ? mid_steps : mid_alt)
                plan.run(i, "rotgen", "implicit_midpoint", "double", 0, h);
            for (double tol : is_main ? tols_rodas : std::vector<double>{})
                plan.run(i, "rotgen", "rodas4", "double", tol, 0);
        }
        if (is_main) {
            // (--quick: the fewest instantiations that still exercise every kind of run)
            for (double tol : tols_float) {
                if (!opt.quick) plan.run(i, "rotgen", "dopri5", "float", tol, 0);
                plan.run(i, "rotgen", "dop853", "float", tol, 0);
            }
            for (std::size_t j = 0; j < rk4_steps.size() && j < 4 && !opt.quick; ++j)
                plan.run(i, "rotgen", "rk4", "float", 0, rk4_steps[j]);
            for (double tol : tols_long) {
                if (!opt.quick) plan.run(i, "rotgen", "dopri5", "long_double", tol, 0);
                plan.run(i, "rotgen", "dop853", "long_double", tol, 0);
            }
            for (std::size_t j = 0; j < rk4_steps.size() && j < 5 && !opt.quick; ++j)
                plan.run(i, "rotgen", "rk4", "long_double", 0, rk4_steps[j]);
            // the peers, on the same kernels
            for (double tol : tols_all)
                plan.run(i, "odeint", "dopri5", "double", tol, 0);
            for (std::size_t j = 0; j < tols_all.size() && !opt.quick; ++j)
                plan.run(i, "odeint", "rkf78", "double", tols_all[j], 0);
            for (std::size_t j = 0; j < rk4_steps.size() && !opt.quick; ++j)
                plan.run(i, "odeint", "rk4", "double", 0, rk4_steps[j]);
            for (double h : high_steps) {
                plan.run(i, "rotgen", "dop853", "double", 0, h);
                if (!opt.quick) plan.run(i, "odeint", "rkf78", "double", 0, h);
            }
            for (double tol : tols_all)
                plan.run(i, "cvode", "adams", "double", tol, 0);
            for (double tol : tols_bdf)
                plan.run(i, "cvode", "bdf", "double", tol, 0);
        }
    }
    // the long runs: 10^6 steps of h = 0.3 / nu (large enough that the explicit methods' drift
    // shows within the run)
    if (opt.long_steps > 0 && variants[0].has_energy && conservative) {
        const double h = 0.3 / nu;
        const double t_end = t0 + double(opt.long_steps) * h;
        const int samples = opt.quick ? 40 : 300;
        const auto drift = [&](std::size_t v, const std::string& method, double tol, double step) {
            std::string label = method + ":" + variants[v].label + ":" +
                                (step > 0 ? "h=" + short_number(step, 3) : "tol=" + tol_text(tol));
            plan.text << "drift " << v << " " << method << " " << plain(tol) << " " << plain(step)
                      << " " << plain(t_end) << " " << samples << " " << label << "\n";
            drift_labels.push_back(label);
            variants[v].drift_methods |= method_bit(method);
        };
        const std::size_t hv = hamiltonian_variant ? *hamiltonian_variant : 0;
        drift(hv, "implicit_midpoint", 0, h);
        drift(hv, "rk4", 0, h);
        if (!opt.quick) {
            drift(hv, "dopri5", 1e-8, 0);
            drift(hv, "dop853", 1e-8, 0);
        }
        if (hv != 0) {
            drift(0, "implicit_midpoint", 0, h);
            drift(0, "rk4", 0, h);
        }
    }
    write_file(dir / "plan.txt", plan.text.str());
}

void bench_run::write_driver_source() {
    std::string kernels;
    for (auto& v : variants) {
        emit_options eo;
        eo.form = v.form;
        eo.strategy = v.strategy;
        eo.outputs = v.outputs;
        eo.specialise_all = v.specialised;
        eo.name = v.unit;
        eo.command = "rotgen bench " + opt.scene;
        v.header = emit_header(spec, d, eo);
        kernels += "// ==== " + v.label + " ====\n" + v.header.text + "\n" + v.naive + "\n";
    }
    std::string structs, list;
    for (std::size_t i = 0; i < variants.size(); ++i) {
        structs += variant_struct(variants[i], i, scene, k0, d) + "\n";
        list += (i ? ", " : "") + std::string("variant_") + std::to_string(i);
    }
    std::string driver_template = read_file(src.harness / "driver.cpp.in");
    const std::map<std::string, std::string> fills{
        {"title", "work-precision driver for " + opt.scene},
        {"command", "rotgen bench " + opt.scene + (opt.quick ? " --quick" : "")},
        {"kernels", kernels},
        {"variants", structs},
        {"variant_list", list}};
    source.clear();
    for (std::size_t i = 0; i < driver_template.size();) {
        const std::size_t at = driver_template.find('@', i);
        if (at == std::string::npos) {
            source += driver_template.substr(i);
            break;
        }
        const std::size_t end = driver_template.find('@', at + 1);
        const auto it = end == std::string::npos
                            ? fills.end()
                            : fills.find(driver_template.substr(at + 1, end - at - 1));
        if (it == fills.end()) {
            source += driver_template.substr(i, at + 1 - i);
            i = at + 1;
            continue;
        }
        source += driver_template.substr(i, at - i) + it->second;
        i = end + 1;
    }
    generate_seconds = std::chrono::duration<double>(clock::now() - t_gen).count();
}

void bench_run::compile_driver() {
    const auto t_compile = clock::now();
    const std::string include = "-I" + shell_quote(src.harness.string()) + " -I" +
                                shell_quote(src.runtime.string()) + " " + eigen_flags();
    const std::string libs = "-lsundials_cvode -lsundials_nvecserial -lsundials_sunmatrixdense "
                             "-lsundials_sunlinsoldense -lsundials_sunnonlinsolfixedpoint";
    std::string harness_text; // the headers the driver includes, in name order (the cache key)
    for (const auto& d : {src.harness, src.runtime}) {
        std::vector<fs::path> headers;
        for (const auto& e : fs::directory_iterator(d))
            if (e.path().extension() == ".hpp") headers.push_back(e.path());
        std::sort(headers.begin(), headers.end());
        for (const auto& h : headers)
            harness_text += read_file(h);
    }
    int status = 0;
    const std::string compiler_id = run_capture(shell_quote(compiler()) + " --version", &status);
    if (status != 0)
        throw std::runtime_error("no working C++ compiler ('" + compiler() + "'): " + compiler_id);
    const bool gcc = compiler_id.find("clang") == std::string::npos &&
                     compiler_id.find("Free Software Foundation") != std::string::npos;
    if (gcc) flags += " --param max-inline-insns-single=2000";
    const std::string key = hex(fnv1a(source + '\0' + harness_text + '\0' + compiler_id + '\0' +
                                      flags + '\0' + libs + '\0' + ROTGEN_VERSION));
    cache = fs::path(cache_directory()) / "bench" / (scene_name + "-" + key);
    std::error_code ec;
    fs::create_directories(cache, ec);
    if (ec)
        throw user_error({cache.string()}, "cannot create the cache directory: " + ec.message());
    exe = cache / "driver";
    cached = fs::exists(exe, ec);
    if (!cached) {
        const fs::path cpp = cache / "driver.cpp";
        write_file(cpp, source);
        const fs::path tmp = exe.string() + ".tmp" + std::to_string(::getpid());
        std::cout << "rotgen bench: compiling the driver (" << variants.size()
                  << " variants; once per scene, cached in " << cache.string() << ") ..."
                  << std::flush;
        const std::string log = run_capture(shell_quote(compiler()) + " " + flags + " " + include +
                                                " " + shell_quote(cpp.string()) + " -o " +
                                                shell_quote(tmp.string()) + " " + libs,
                                            &status);
        if (status != 0) {
            fs::remove(tmp, ec);
            throw std::runtime_error("compiling the work-precision driver failed (" + cpp.string() +
                                     "):\n" + log.substr(0, 4000));
        }
        fs::rename(tmp, exe, ec);
        if (ec) throw std::runtime_error("cannot install " + exe.string() + ": " + ec.message());
        std::cout << " done\n";
    }
    compile_seconds = std::chrono::duration<double>(clock::now() - t_compile).count();
}

void bench_run::run_driver() {
    const auto load_average = [] {
        std::ifstream in("/proc/loadavg");
        std::string one;
        in >> one;
        return one.empty() ? std::string("?") : one;
    };
    load_before = load_average();
    const auto t_run = clock::now();
    raw = dir / "raw.txt";
    std::cout << "rotgen bench: running the sweep (" << plan.lines << " configurations) ..."
              << std::flush;
    int status = 0;
    const std::string log =
        run_capture(shell_quote(exe.string()) + " " + shell_quote((dir / "plan.txt").string()) +
                        " " + shell_quote(raw.string()),
                    &status);
    if (status != 0)
        throw std::runtime_error("the work-precision driver failed (status " +
                                 std::to_string(status) + "): " + log.substr(0, 2000));
    std::cout << " done\n";
    run_seconds = std::chrono::duration<double>(clock::now() - t_run).count();
    load_after = load_average();
}

void bench_run::read_output() {
    {
        std::ifstream in(raw);
        std::string line;
        while (std::getline(in, line)) {
            std::istringstream is(line);
            std::string what;
            is >> what;
            if (what == "compared") {
                std::getline(is, compared);
                if (!compared.empty() && compared[0] == ' ') compared.erase(0, 1);
            } else if (what == "reference") {
                std::string e, o;
                is >> reference_source >> e >> o;
                reference_error = parse_number(e);
                reference_orientation = parse_number(o);
            } else if (what == "reference_run") {
                std::string rest;
                std::getline(is, rest);
                reference_runs.push_back(rest);
            } else if (what == "row") {
                result_row r;
                std::string tol, step, err, orient, med, mn, mx, ed, md;
                std::size_t n = 0;
                is >> r.variant >> r.peer >> r.method >> r.form >> r.scalar >> tol >> step >>
                    r.status >> err >> orient >> r.rhs >> r.jac >> r.steps >> med >> mn >> mx >>
                    ed >> md >> n;
                r.tol = parse_number(tol);
                r.step = parse_number(step);
                r.error = parse_number(err);
                r.orientation = parse_number(orient);
                r.median = parse_number(med);
                r.min = parse_number(mn);
                r.max = parse_number(mx);
                r.energy_drift = parse_number(ed);
                r.momentum_drift = parse_number(md);
                for (std::size_t i = 0; i < n; ++i) {
                    std::string v;
                    is >> v;
                    r.y.push_back(v);
                }
                rows.push_back(std::move(r));
            } else if (what == "drift") {
                drift_point p;
                std::string t, e;
                is >> p.label >> p.steps >> p.rhs >> t >> e;
                p.t = parse_number(t);
                p.e = parse_number(e);
                drift_points.push_back(p);
            } else if (what == "drift_failed") {
                std::string label, why;
                is >> label >> why;
                drift_failed[label] = why;
            }
        }
    }
    if (rows.empty())
        throw std::runtime_error("the work-precision driver wrote no results (" + raw.string() +
                                 ")");
}

void bench_run::write_tables() {
    {
        std::ostringstream csv;
        csv << "method,peer,form,scalar,tolerance,step,error,orientation_error,rhs_evals,jac_evals,"
               "time_median_s,time_min_s,time_max_s,energy_drift\n";
        std::ostringstream fin;
        fin << "method,peer,form,scalar,tolerance,step,status,rhs_evals,state\n";
        for (const auto& r : rows) {
            const std::string tol = r.tol > 0 ? short_number(r.tol, 6) : "";
            const std::string step = r.step > 0 ? short_number(r.step, 17) : "";
            csv << r.method << "," << r.peer << "," << r.form << "," << r.scalar << "," << tol
                << "," << step << "," << (r.status == "ok" ? csv_number(r.error) : "") << ","
                << (r.status == "ok" ? csv_number(r.orientation) : "") << "," << r.rhs << ","
                << r.jac << "," << csv_number(r.median) << "," << csv_number(r.min) << ","
                << csv_number(r.max) << "," << (r.status == "ok" ? csv_number(r.energy_drift) : "")
                << "\n";
            fin << r.method << "," << r.peer << "," << r.form << "," << r.scalar << "," << tol
                << "," << step << "," << r.status << "," << r.rhs << ",";
            for (std::size_t i = 0; i < r.y.size(); ++i)
                fin << (i ? " " : "") << r.y[i];
            fin << "\n";
        }
        write_file(dir / "results.csv", csv.str());
        write_file(dir / "final_states.csv", fin.str());
    }
    {
        std::ostringstream dc;
        dc << "label,t,relative_energy_error,steps,rhs_evals\n";
        for (const auto& p : drift_points)
            dc << p.label << "," << short_number(p.t, 10) << "," << short_number(p.e, 6) << ","
               << p.steps << "," << p.rhs << "\n";
        write_file(dir / "drift.csv", dc.str());
    }
}

void bench_run::summarise() {
    const auto is_peer = [](const result_row& r) { return r.peer != "rotgen"; };
    levels.clear();
    for (int e = 3; e <= 13; ++e)
        levels.push_back(std::pow(10.0, -e));
    best.assign(levels.size(), best_entry{});
    for (std::size_t l = 0; l < levels.size(); ++l)
        for (const auto& r : rows) {
            if (!r.ok() || !(r.error <= levels[l]) || !std::isfinite(r.median)) continue;
            const result_row*& slot = is_peer(r) ? best[l].peer : best[l].rotgen;
            if (!slot || r.median < slot->median) slot = &r;
        }
    // The same, interpolated along each configuration's curve: between two neighbouring points
    // (by tolerance or step) whose errors straddle the level, log(time) and log(RHS evaluations)
    // are interpolated linearly in log(error); a point at or below the level counts as it is.
    std::map<std::string, std::vector<const result_row*>> curves_by_name;
    for (const auto& r : rows)
        if (r.ok() && std::isfinite(r.median) && r.error > 0)
            curves_by_name[(r.peer == "rotgen" ? "rotgen " : r.peer + " ") + method_key(r) + " " +
                           r.scalar + " " + r.form]
                .push_back(&r);
    reached.assign(levels.size(), {}); // (rotgen, peer)
    for (auto& [name, points] : curves_by_name) {
        std::sort(points.begin(), points.end(), [](const result_row* a, const result_row* b) {
            return a->tol > 0 ? a->tol > b->tol : a->step > b->step;
        });
        for (std::size_t l = 0; l < levels.size(); ++l) {
            const double level = levels[l];
            reach best_here;
            best_here.curve = name;
            best_here.peer = points.front()->peer != "rotgen";
            for (std::size_t i = 0; i < points.size(); ++i) {
                const result_row& b = *points[i];
                if (b.error <= level && !(b.median >= best_here.time))
                    best_here.time = b.median, best_here.rhs = double(b.rhs);
                if (i == 0) continue;
                const result_row& a = *points[i - 1];
                if (!(a.error > level && b.error <= level)) continue;
                const double w =
                    (std::log(level) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
                const double t =
                    std::exp(std::log(a.median) + w * (std::log(b.median) - std::log(a.median)));
                const double n = std::exp(std::log(double(a.rhs)) +
                                          w * (std::log(double(b.rhs)) - std::log(double(a.rhs))));
                if (!(t >= best_here.time)) best_here.time = t, best_here.rhs = n;
            }
            if (!std::isfinite(best_here.time)) continue;
            reach& slot = best_here.peer ? reached[l].second : reached[l].first;
            if (!(best_here.time >= slot.time)) slot = best_here;
        }
    }
}

void bench_run::write_markdown() {
    const double wall_seconds_so_far = std::chrono::duration<double>(clock::now() - wall0).count();
    std::ostringstream md;
    md << "# Work-precision: " << scene_name << "\n\n"
       << "Scene `" << opt.scene << "` (model `" << spec.name << "`, " << to_string(scene.form)
       << " form), t from " << plain(t0) << " to " << plain(t1) << ". Generated by `rotgen bench "
       << opt.scene << (opt.quick ? " --quick" : "") << "`.\n\n";
    md << "- **error**: max-norm at the end time over the quantities every configuration "
          "determines: "
       << compared << " (each form's final state mapped to them; phi, psi modulo 2 pi).\n"
       << "- **orientation_error**: the angle of A_ref A^T, for forms that determine the "
          "attitude.\n"
       << "- **reference**: ";
    if (reference_source.rfind("exact", 0) == 0)
        md << "exact (free body, " << reference_source.substr(6)
           << " top: omega in Jacobi elliptic / circular functions, the attitude from the "
              "conserved "
              "angular momentum with phi by Gauss-Kronrod quadrature); DOP853 in long double at "
              "rtol "
              "2e-18 differs from it by "
           << short_number(reference_error) << " (orientation "
           << short_number(reference_orientation) << ").\n";
    else
        md << "DOP853 in long double at rtol = atol = 2e-18 on `" << variants[ref_variant].label
           << "`; a run at 2e-16 differs from it by " << short_number(reference_error)
           << " (orientation " << short_number(reference_orientation)
           << "), an upper estimate of the reference's own error.\n";
    md << "- **time**: median (min, max) of " << repeats
       << " repeats, each a loop of whole integrations lasting >= " << short_number(target * 1e3)
       << " ms, divided by the loop length; one process, one "
          "translation unit (kernels, integrators and peers compiled together with `"
       << flags
       << "`). Load average (1 min) of the machine before / after the sweep: " << load_before
       << " / " << load_after
       << " — other processes share the cores, so compare medians with their min.\n"
       << "- **tolerance**: rtol = atol = tol for every adaptive method and peer; fixed-step "
          "methods list their step. `dop853 fixed` and `odeint rkf78 fixed` are DOP853 and "
          "Fehlberg 7(8) with a fixed step and no error control (what the control costs).\n"
       << "- **forms**: every variant is specialised (parameters folded) and lowered (CSE) unless "
          "labelled `+runtime` or `+unlowered`.\n"
       << "- **energy_drift**: |E(t_end) - E(t0)| / |E(t0)|; momentum drift (results.md only): the "
          "same for the momenta of the cyclic coordinates.\n\n";
    md << "## Best configuration per accuracy\n\n"
       << "Fastest configuration (by median time) whose error is at most the level; time as median "
          "(min).\n\n"
       << "| error <= | rotgen best | time | RHS evals | best peer | time | RHS evals | peer / "
          "rotgen |\n"
       << "|---|---|---:|---:|---|---:|---:|---:|\n";
    for (std::size_t l = 0; l < levels.size(); ++l) {
        const auto* a = best[l].rotgen;
        const auto* b = best[l].peer;
        md << "| " << tol_text(levels[l]) << " | " << config_name(a) << " | "
           << (a ? short_number(a->median * 1e6) + " µs (" + short_number(a->min * 1e6) + ")" : "")
           << " | " << (a ? std::to_string(a->rhs) : "") << " | " << config_name(b) << " | "
           << (b ? short_number(b->median * 1e6) + " µs (" + short_number(b->min * 1e6) + ")" : "")
           << " | " << (b ? std::to_string(b->rhs) : "") << " | "
           << (a && b ? short_number(b->median / a->median, 3) + "×" : "") << " |\n";
    }
    md << "\n### Interpolated along each curve\n\n"
       << "Time (median) to reach the accuracy on each configuration's error-time curve, "
          "interpolated between its neighbouring points; the fastest rotgen and the fastest peer "
          "configuration.\n\n"
       << "| error | rotgen configuration | time | RHS evals | peer configuration | time | RHS "
          "evals "
          "| peer / rotgen |\n|---|---|---:|---:|---|---:|---:|---:|\n";
    for (std::size_t l = 0; l < levels.size(); ++l) {
        const reach& a = reached[l].first;
        const reach& b = reached[l].second;
        const bool ha = std::isfinite(a.time), hb = std::isfinite(b.time);
        md << "| " << tol_text(levels[l]) << " | " << (ha ? a.curve : "—") << " | "
           << (ha ? short_number(a.time * 1e6) + " µs" : "") << " | "
           << (ha ? short_number(a.rhs, 4) : "") << " | " << (hb ? b.curve : "—") << " | "
           << (hb ? short_number(b.time * 1e6) + " µs" : "") << " | "
           << (hb ? short_number(b.rhs, 4) : "") << " | "
           << (ha && hb ? short_number(b.time / a.time, 3) + "×" : "") << " |\n";
    }
    md << "\n## Fewest RHS evaluations per accuracy (" << variants[0].label << ", double)\n\n"
       << "| error <= | rotgen dop853 | rotgen dopri5 | odeint rkf78 | odeint dopri5 | cvode adams "
          "| cvode bdf |\n"
       << "|---|---:|---:|---:|---:|---:|---:|\n";
    for (double level : levels) {
        md << "| " << tol_text(level);
        for (const auto& [peer, method] :
             std::vector<std::pair<std::string, std::string>>{{"rotgen", "dop853"},
                                                              {"rotgen", "dopri5"},
                                                              {"odeint", "rkf78"},
                                                              {"odeint", "dopri5"},
                                                              {"cvode", "adams"},
                                                              {"cvode", "bdf"}}) {
            const result_row* b = fewest(rows, peer, method, level);
            md << " | " << (b ? std::to_string(b->rhs) : "");
        }
        md << " |\n";
    }
    if (!drift_labels.empty()) {
        md << "\n## Long run: relative energy error (" << opt.long_steps
           << " steps of h = " << short_number(0.3 / nu)
           << "; adaptive runs over the same time)\n\n"
           << "| run | steps | RHS evals | first sample | largest | at the end |\n"
           << "|---|---:|---:|---:|---:|---:|\n";
        for (const auto& label : drift_labels) {
            const drift_point* first = nullptr;
            const drift_point* last = nullptr;
            double largest = 0;
            for (const auto& p : drift_points)
                if (p.label == label) {
                    if (!first) first = &p;
                    last = &p;
                    largest = std::max(largest, p.e);
                }
            md << "| " << label << " | " << (last ? std::to_string(last->steps) : "") << " | "
               << (last ? std::to_string(last->rhs) : "") << " | "
               << (first ? short_number(first->e) : "") << " | "
               << (last ? short_number(largest) : "") << " | "
               << (last                        ? short_number(last->e)
                   : drift_failed.count(label) ? drift_failed[label]
                                               : "")
               << " |\n";
        }
    }
    md << "\n## All configurations\n\n"
       << "| method | peer | form | scalar | tol | step | status | error | orientation | RHS | Jac "
          "| "
          "steps | median µs | min µs | max µs | energy drift | momentum drift |\n"
       << "|---|---|---|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& r : rows)
        md << "| " << r.method << " | " << r.peer << " | " << r.form << " | " << r.scalar << " | "
           << (r.tol > 0 ? tol_text(r.tol) : "") << " | "
           << (r.step > 0 ? short_number(r.step, 4) : "") << " | " << r.status << " | "
           << short_number(r.error) << " | " << short_number(r.orientation) << " | " << r.rhs
           << " | " << r.jac << " | " << r.steps << " | " << short_number(r.median * 1e6) << " | "
           << short_number(r.min * 1e6) << " | " << short_number(r.max * 1e6) << " | "
           << short_number(r.energy_drift) << " | " << short_number(r.momentum_drift) << " |\n";
    md << "\nGeneration " << short_number(generate_seconds) << " s, compilation "
       << (cached ? "cached" : short_number(compile_seconds) + " s") << ", sweep "
       << short_number(run_seconds) << " s; total so far " << short_number(wall_seconds_so_far)
       << " s (plots follow). Driver: `" << (cache / "driver.cpp").string() << "`.\n";
    markdown = md.str();
}

void bench_run::draw_plots() {
    // Curves: one per (peer, method, form, scalar), sorted by tolerance or step; panels group
    // (a) the integrators and peers on the main form in double, (b) the forms and code
    // generation, (c) the scalar types.
    std::error_code ec;
    std::vector<curve> curves;
    const auto color_of = [](const std::string& peer, const std::string& method) {
        static const std::map<std::string, int> colors{
            {"rotgen rk4", 1},    {"rotgen dopri5", 2},
            {"rotgen dop853", 3}, {"rotgen implicit_midpoint", 4},
            {"rotgen rodas4", 5}, {"odeint dopri5", 6},
            {"odeint rkf78", 7},  {"odeint rk4", 8},
            {"cvode adams", 9},   {"cvode bdf", 10},
            {"rotgen dop853 fixed", 11}, {"odeint rkf78 fixed", 12}};
        const auto it = colors.find(peer + " " + method);
        return it == colors.end() ? 13 : it->second;
    };
    for (const auto& r : rows) {
        if (!r.ok() || !(r.error > 0) || !std::isfinite(r.median)) continue;
        std::vector<std::string> panels;
        const bool main_double = r.variant == 0 && r.scalar == "double";
        const std::string m = method_key(r);
        if (main_double) panels.push_back("a");
        if (r.peer == "rotgen" && r.scalar == "double" &&
            (m == "dop853" || m == "rk4" || m == "implicit_midpoint"))
            panels.push_back("b");
        if (r.peer == "rotgen" && r.variant == 0 && (m == "dop853" || m == "dopri5" || m == "rk4"))
            panels.push_back("c");
        for (const auto& panel : panels) {
            const std::string key =
                panel + "|" + r.peer + "|" + m + "|" + r.form + "|" + r.scalar;
            auto it = std::find_if(curves.begin(), curves.end(),
                                   [&](const curve& c) { return c.key == key; });
            if (it == curves.end()) {
                curve c;
                c.key = key;
                c.panel = panel;
                c.title = method_title(r) + (panel == "b" ? " " + r.form : "") +
                          (panel == "c" ? " " + r.scalar : "");
                c.color = panel == "a" ? color_of(r.peer, m) : 0;
                c.dash = r.peer == "rotgen" ? 1 : r.peer == "odeint" ? 2 : 3;
                c.point = panel == "a" ? color_of(r.peer, m) : 1;
                curves.push_back(c);
                it = curves.end() - 1;
            }
            it->points.push_back(&r);
        }
    }
    // colours within panels b and c: by form / scalar; dash by method
    {
        std::map<std::string, int> form_colors, scalar_colors;
        for (auto& c : curves) {
            const result_row& r = *c.points.front();
            if (c.panel == "b") {
                if (!form_colors.count(r.form)) form_colors[r.form] = int(form_colors.size()) + 1;
                c.color = form_colors[r.form];
                c.dash = r.method == "dop853" ? 1 : r.method == "rk4" ? 2 : 4;
                c.point = r.method == "dop853" ? 7 : r.method == "rk4" ? 5 : 9;
            } else if (c.panel == "c") {
                if (!scalar_colors.count(r.scalar))
                    scalar_colors[r.scalar] = int(scalar_colors.size()) + 1;
                c.color = scalar_colors[r.scalar];
                c.dash = r.method == "dop853" ? 1 : r.method == "dopri5" ? 2 : 4;
                c.point = r.method == "dop853" ? 7 : r.method == "dopri5" ? 5 : 9;
            }
            std::sort(c.points.begin(), c.points.end(),
                      [](const result_row* a, const result_row* b) {
                          return a->tol > 0 ? a->tol > b->tol : a->step > b->step;
                      });
        }
    }
    {
        std::ostringstream data;
        for (const auto& c : curves) {
            data << "# " << c.title << "\n";
            for (const auto* r : c.points)
                data << plain(r->median) << " " << r->rhs << " " << plain(r->error) << "\n";
            data << "\n\n";
        }
        write_file(dir / "plot_data.dat", data.str());
    }
    const std::string palette =
        "set linetype 1 lc rgb '#1f77b4'\nset linetype 2 lc rgb '#ff7f0e'\nset linetype 3 lc rgb "
        "'#2ca02c'\nset linetype 4 lc rgb '#d62728'\nset linetype 5 lc rgb '#9467bd'\nset linetype "
        "6 lc rgb '#8c564b'\nset linetype 7 lc rgb '#e377c2'\nset linetype 8 lc rgb '#7f7f7f'\nset "
        "linetype 9 lc rgb '#bcbd22'\nset linetype 10 lc rgb '#17becf'\nset linetype 11 lc rgb "
        "'#000000'\n";
    const auto work_precision_plot = [&](const std::string& file, int column,
                                         const std::string& xlabel) {
        const fs::path png = dir / file;
        const fs::path tmp_png = png.string() + ".tmp" + std::to_string(::getpid()) + ".png";
        std::ostringstream gp;
        gp << "set terminal pngcairo size 1600,1500 noenhanced font ',10'\n"
           << "set output '" << gnuplot_escape(tmp_png.string()) << "'\n"
           << palette << "set logscale xy\nset grid\nset format y '1e%T'\nset format x '1e%T'\n"
           << "set key outside right top Left reverse samplen 3\n"
           << "set xlabel '" << xlabel << "'\nset ylabel 'error at t = " << plain(t1)
           << " (max-norm)'\n"
           << "set multiplot layout 3,1 title '" << gnuplot_escape(scene_name)
           << ": work-precision (" << gnuplot_escape(compared)
           << "); solid rotgen, dashed Odeint, dotted CVODE'\n";
        const std::vector<std::pair<std::string, std::string>> panel_titles{
            {"a", "integrators and peers on " + variants[0].label + " (double)"},
            {"b", "formulations and code generation (rotgen, double): solid dop853, dashed rk4, "
                  "dotted midpoint"},
            {"c",
             "scalar types on " + variants[0].label + ": solid dop853, dashed dopri5, dotted rk4"}};
        for (const auto& [panel, title] : panel_titles) {
            gp << "set title '" << gnuplot_escape(title) << "'\nplot ";
            bool first = true;
            for (std::size_t i = 0; i < curves.size(); ++i) {
                if (curves[i].panel != panel) continue;
                gp << (first ? "" : ", \\\n     ") << "'"
                   << gnuplot_escape((dir / "plot_data.dat").string()) << "' index " << i
                   << " using " << column << ":3 with linespoints lt " << curves[i].color << " dt "
                   << curves[i].dash << " pt " << curves[i].point << " ps 0.8 lw 1.5 title '"
                   << gnuplot_escape(curves[i].title) << "'";
                first = false;
            }
            if (first) gp << "1/0 notitle";
            gp << "\n";
        }
        gp << "unset multiplot\n";
        run_gnuplot(dir / (file + ".gp"), gp.str(), png);
        fs::rename(tmp_png, png, ec);
        if (ec) throw user_error({png.string()}, "cannot write: " + ec.message());
    };
    work_precision_plot("work_precision_time.png", 1,
                        "time per integration (s), median of " + std::to_string(repeats));
    work_precision_plot("work_precision_evals.png", 2, "RHS evaluations");
    if (!drift_labels.empty()) {
        std::ostringstream data;
        for (const auto& label : drift_labels) {
            data << "# " << label << "\n";
            for (const auto& p : drift_points)
                if (p.label == label && p.t > t0)
                    data << plain(p.t - t0) << " " << plain(std::max(p.e, 1e-19)) << "\n";
            data << "\n\n";
        }
        write_file(dir / "drift_data.dat", data.str());
        const fs::path png = dir / "invariant_drift.png";
        const fs::path tmp_png = png.string() + ".tmp" + std::to_string(::getpid()) + ".png";
        std::ostringstream gp;
        gp << "set terminal pngcairo size 1100,650 noenhanced font ',10'\n"
           << "set output '" << gnuplot_escape(tmp_png.string()) << "'\n"
           << palette << "set logscale xy\nset grid\nset format y '1e%T'\n"
           << "set key outside right top Left reverse\n"
           << "set xlabel 't - t0'\nset ylabel '|E(t) - E(0)| / |E(0)|'\n"
           << "set title '" << gnuplot_escape(scene_name) << ": energy error over "
           << opt.long_steps << " steps of h = " << short_number(0.3 / nu)
           << " (adaptive runs over the same time)'\n"
           << "plot ";
        for (std::size_t i = 0; i < drift_labels.size(); ++i)
            gp << (i ? ", \\\n     " : "") << "'"
               << gnuplot_escape((dir / "drift_data.dat").string()) << "' index " << i
               << " using 1:2 with lines lw 1.5 lt " << (i + 1) << " title '"
               << gnuplot_escape(drift_labels[i]) << "'";
        gp << "\n";
        run_gnuplot(dir / "invariant_drift.gp", gp.str(), png);
        fs::rename(tmp_png, png, ec);
        if (ec) throw user_error({png.string()}, "cannot write: " + ec.message());
    }
}

void bench_run::finish() {
    wall_seconds = std::chrono::duration<double>(clock::now() - wall0).count();
    markdown +=
        "\nWall time of the whole `rotgen bench` run: " + short_number(wall_seconds) + " s.\n";
    write_file(dir / "results.md", markdown);
    std::size_t failed = 0;
    for (const auto& r : rows)
        failed += r.status != "ok";
    std::cout << "rotgen bench " << opt.scene << "\n"
              << "  variants  ";
    for (std::size_t i = 0; i < variants.size(); ++i)
        std::cout << (i ? ", " : "") << variants[i].label;
    std::cout << "\n  reference " << reference_source << " (check " << short_number(reference_error)
              << ")\n  compared  " << compared << "\n"
              << "  runs      " << rows.size() << " configurations (" << failed << " failed), "
              << drift_labels.size() << " long runs\n"
              << "  time      " << short_number(generate_seconds) << " s generating, "
              << (cached ? std::string("cached driver")
                         : short_number(compile_seconds) + " s compiling")
              << ", " << short_number(run_seconds) << " s sweeping, " << short_number(wall_seconds)
              << " s in all\n"
              << "  harness   " << src.harness.string() << ", runtime " << src.runtime.string()
              << "\n";
    std::cout << "  fastest to reach an error (interpolated along each curve; median times):\n";
    for (std::size_t l = 0; l < levels.size(); ++l) {
        const reach& a = reached[l].first;
        const reach& b = reached[l].second;
        if (!std::isfinite(a.time) && !std::isfinite(b.time)) continue;
        std::cout << "  " << tol_text(levels[l]) << "  rotgen "
                  << (std::isfinite(a.time) ? short_number(a.time * 1e6) + " us (" + a.curve + ")"
                                            : "-")
                  << "  peer "
                  << (std::isfinite(b.time) ? short_number(b.time * 1e6) + " us (" + b.curve + ")"
                                            : "-")
                  << "\n";
    }
    std::cout << "  wrote     " << (dir / "results.csv").string()
              << ", results.md, final_states.csv, "
              << "drift.csv, work_precision_time.png, work_precision_evals.png"
              << (drift_labels.empty() ? "" : ", invariant_drift.png") << "\n";
}

} // namespace

int cmd_bench(const std::vector<std::string>& args) {
    return bench_run().run(args);
}

} // namespace rotgen
