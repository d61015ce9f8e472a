// rotgen simulate SCENE.yaml [-o out.csv] [--plot out.png]
//
// derive -> emit the scene's form -> compile it (cached shared object) -> load -> integrate with the
// runtime -> write the recorded quantities (CSV, header `t,<names>`) -> plot (gnuplot).
// Angles are z-x-z Euler angles (passive A = Az(psi) Ax(theta) Az(phi), 5.25), omega in body axes.
#include "simulate/simulate.hpp"
#include "derive/derive.hpp"
#include "emit/emit.hpp"
#include "support/error.hpp"
#include "forms/forms.hpp"
#include "run/compile_cache.hpp"
#include "support/hash.hpp"
#include "support/process.hpp"
#include "lower/lower.hpp"
#include "expr/numbers.hpp"
#include "expr/print.hpp"
#include "scene/scene.hpp"
#include "expr/symbols.hpp"

#include <rotgen.hpp>

#include <unistd.h>

#include <Eigen/Dense>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

namespace rotgen {

namespace {

using GiNaC::ex;

struct simulate_options {
    std::string scene, csv, plot;
};

simulate_options parse_arguments(const std::vector<std::string>& args) {
    const auto usage = [](const std::string& problem) {
        return user_error({"rotgen simulate"}, problem);
    };
    simulate_options o;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "-o" || a == "--plot") {
            if (i + 1 >= args.size()) throw usage(a + " needs a file name");
            (a == "-o" ? o.csv : o.plot) = args[++i];
        } else if (!a.empty() && a[0] == '-') {
            throw usage("unknown option '" + a + "' for simulate");
        } else if (o.scene.empty()) {
            o.scene = a;
        } else {
            throw usage("simulate takes one scene file, got '" + o.scene + "' and '" + a + "'");
        }
    }
    if (o.scene.empty()) throw usage("simulate needs a scene file");
    return o;
}

double number(const ex& e, const GiNaC::exmap& at) {
    const ex v = GiNaC::evalf(e.subs(at));
    if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
        throw std::logic_error("simulate: expression did not evaluate to a real number");
    return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

std::string format_number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

// Three significant digits, for the summary.
std::string short_number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

// An output file is written to a temporary beside it, then renamed: never a partial file.
class output_file {
  public:
    explicit output_file(std::string path)
        : m_path(std::move(path)), m_tmp(m_path + ".tmp" + std::to_string(::getpid())) {
        m_out.open(m_tmp, std::ios::binary);
        if (!m_out) throw user_error({m_path}, std::string("cannot write: ") + std::strerror(errno));
    }
    ~output_file() {
        if (!m_done) std::remove(m_tmp.c_str());
    }
    std::ostream& stream() { return m_out; }
    const std::string& temporary() const { return m_tmp; }
    void commit() {
        m_out.close();
        if (!m_out || std::rename(m_tmp.c_str(), m_path.c_str()) != 0)
            throw user_error({m_path}, std::string("cannot write: ") + std::strerror(errno));
        m_done = true;
    }

  private:
    std::string m_path, m_tmp;
    std::ofstream m_out;
    bool m_done = false;
};

// The initial state, in every coordinate the forms use.
struct initial_state {
    std::array<double, 3> q{}, qd{}, p{}, omega{};
    bool have_rates = true;
};

initial_state initial_kinematics(const scene_spec& scene, const derivation& d,
                                 const GiNaC::exmap& parameters) {
    const auto& s = symbols();
    initial_state k;
    k.q = scene.angles;
    GiNaC::exmap at = parameters;
    for (int i = 0; i < 3; ++i) at[s.q[i]] = float_numeric(k.q[i]);
    const double sin_theta = std::sin(k.q[1]);
    const bool singular = std::abs(sin_theta) < 1e-12;
    switch (scene.initial) {
    case initial_kind::rates:
        k.qd = scene.initial_rates;
        break;
    case initial_kind::momenta: {
        if (singular)
            throw user_error(scene.initial_where,
                             "momenta cannot give the rates at theta = 0 or pi (the mass matrix is "
                             "singular there); give body omega1..3 instead");
        Eigen::Matrix3d M;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) M(i, j) = number(d.mass_matrix[i][j], at);
        const Eigen::Vector3d qd =
            M.ldlt().solve(Eigen::Vector3d(scene.initial_rates[0], scene.initial_rates[1],
                                           scene.initial_rates[2]));
        for (int i = 0; i < 3; ++i) k.qd[i] = qd[i];
        break;
    }
    case initial_kind::omega:
        k.omega = scene.initial_rates;
        if (singular) {
            k.have_rates = false;
        } else { // q_dot = J^{-1} omega
            for (int i = 0; i < 3; ++i) {
                double r = 0;
                for (int j = 0; j < 3; ++j) r += number(d.inverse_omega_jacobian[i][j], at) * k.omega[j];
                k.qd[i] = r;
            }
        }
        break;
    }
    if (k.have_rates) {
        // a rate from omega may be subnormal (omega1 sin(psi) / sin(theta) with tiny omega1, psi)
        for (int i = 0; i < 3; ++i) at[s.qd[i]] = float_numeric(k.qd[i]);
        for (int i = 0; i < 3; ++i) {
            k.p[i] = number(d.momenta[i], at);
            if (scene.initial != initial_kind::omega) k.omega[i] = number(d.omega[i], at);
        }
    }
    return k;
}

// A system whose kernels were compiled and loaded at run time (runtime/system.hpp concept).
struct loaded_system {
    using kernel = void (*)(double, const double*, double*);
    kernel f = nullptr, jac = nullptr;
    std::size_t n = 0;
    std::size_t size() const { return n; }
    void rhs(double t, const double* y, double* dydt) const { f(t, y, dydt); }
    void jacobian(double t, const double* y, double* J) const { jac(t, y, J); }
};

// `energy0`: the energy at the start; its panel shows energy - energy(0), the drift.
void plot(const std::string& png, const std::string& csv, const std::vector<std::string>& record,
          const std::string& title, double energy0) {
    // One panel per kind of quantity, in the order first recorded.
    std::vector<std::pair<std::string, std::vector<std::string>>> panels;
    const auto panel_of = [](const std::string& name) -> std::string {
        if (name == "phi" || name == "theta" || name == "psi") return "angles (rad)";
        if (name.size() > 4 && name.substr(name.size() - 4) == "_dot") return "angle rates (rad/time)";
        if (name.rfind("p_", 0) == 0) return "momenta";
        if (name.rfind("omega", 0) == 0) return "body angular velocity";
        if (name.rfind("body_", 0) == 0) return "body axis " + name.substr(5) + " in space";
        if (name == "energy") return "energy - energy(0)";
        return name;
    };
    int column = 2;
    for (const auto& name : record) {
        const std::string p = panel_of(name);
        auto it = std::find_if(panels.begin(), panels.end(), [&](const auto& x) { return x.first == p; });
        if (it == panels.end()) {
            panels.push_back({p, {}});
            it = panels.end() - 1;
        }
        for (const auto& c : record_columns(name)) {
            const std::string y = name == "energy" ? "($" + std::to_string(column) + " - (" +
                                                         format_number(energy0) + "))"
                                                   : std::to_string(column);
            it->second.push_back("'" + csv + "' using 1:" + y + " with lines title '" + c + "'");
            ++column;
        }
    }
    output_file out(png); // gnuplot writes the temporary; committed only if it succeeds
    std::ostringstream script;
    script << "set terminal pngcairo size 1000," << 120 + 260 * panels.size() << " noenhanced\n"
           << "set output '" << out.temporary() << "'\n"
           << "set datafile separator ','\nset key outside right\nset grid\n"
           << "set multiplot layout " << panels.size() << ",1 title '" << title << "'\n";
    for (std::size_t i = 0; i < panels.size(); ++i) {
        script << "set ylabel '" << panels[i].first << "'\n";
        script << (i + 1 == panels.size() ? "set xlabel 't'\n" : "unset xlabel\n");
        script << "plot ";
        for (std::size_t j = 0; j < panels[i].second.size(); ++j)
            script << (j ? ", " : "") << panels[i].second[j];
        script << "\n";
    }
    script << "unset multiplot\n";
    const std::string script_path = out.temporary() + ".gp";
    std::ofstream(script_path) << script.str();
    const int status = std::system(("gnuplot " + shell_quote(script_path) + " 2>&1").c_str());
    std::remove(script_path.c_str());
    if (status != 0)
        throw user_error({png}, "gnuplot failed to draw the plot (is gnuplot-nox installed?)");
    out.commit();
}

// Where a recorded column (or a monitored invariant) comes from in one compiled form.
struct value_source {
    enum kind_t {
        compiled,           // an output of the compiled record program
        angle,              // body form: Euler angle `index` of the quaternion
        euler_rate,         // body form: q_dot = J^{-1} omega (5.30), undefined at theta = 0, pi
        canonical_momentum, // body form: p = J^T I omega
    } kind;
    int index;
};

// The expression for a recorded quantity in the form's state, if the form gives it.
std::optional<ex> record_expression(const form_expressions& f, const std::string& name) {
    for (const auto& v : f.state)
        if (v.name == name) return v.symbol;
    for (const auto& [output, o] : f.outputs)
        for (std::size_t i = 0; i < o.names.size() && i < o.values.size(); ++i)
            if (o.names[i] == name && output != "rotation") return o.values[i];
    for (std::size_t i = 0; i < f.rate_names.size() && i < f.rates.size(); ++i)
        if (f.rate_names[i] == name) return f.rates[i];
    return std::nullopt;
}

// One form of the scene's model: emitted, compiled, loaded, with a record program that computes
// the recorded columns and the monitored invariants from the form's state.
struct compiled_form {
    form_kind form = form_kind::lagrangian;
    form_expressions f;
    loaded_library lib;
    loaded_system sys;
    loaded_system::kernel record = nullptr;
    std::vector<value_source> columns;    // one per quantity column (body_x expands to 3)
    std::vector<value_source> invariants; // as scene invariants are listed
    std::size_t outputs = 0;
    double seconds = 0; // deriving the form, emitting and compiling (or loading)
};

struct invariant {
    std::string name;
    bool conserved;
};

compiled_form compile_form(const scene_spec& scene, const derivation& d, form_kind form,
                           bool orientation, const std::vector<invariant>& invariants,
                           const std::string& command) {
    const auto t0 = std::chrono::steady_clock::now();
    const model_spec& spec = scene.model;
    compiled_form c;
    c.form = form;
    c.f = build_form(spec, d, form, lagrangian_strategy::explicit_inverse, orientation);
    const form_expressions& f = c.f;
    emit_options eo;
    eo.form = form;
    eo.outputs = {"rhs", "jacobian"};
    if (form == form_kind::body && orientation) eo.outputs.push_back("rotation");
    eo.command = command;
    const emitted_header header = emit_header(spec, d, eo);
    // The compiled kernels and the state built here must agree on the layout.
    const std::string size_decl = "state_size = " + std::to_string(f.state.size()) + ";";
    if (header.text.find(size_decl) == std::string::npos)
        throw std::logic_error("simulate: the emitted " + header.unit + " does not have " + size_decl);

    // Where each quantity comes from: the form's own expressions where it has them; in the body
    // form the Euler-angle quantities are computed here from the quaternion and omega.
    std::vector<ex> program;
    const bool body_with_angles = form == form_kind::body && orientation;
    const auto source_of = [&](const std::string& name, const source_location& where) -> value_source {
        if (auto e = record_expression(f, name)) {
            program.push_back(*e);
            return {value_source::compiled, static_cast<int>(program.size() - 1)};
        }
        for (int i = 0; i < 3 && body_with_angles; ++i) {
            const std::string& q = coordinate_names()[i];
            if (name == q) return {value_source::angle, i};
            if (name == q + "_dot") return {value_source::euler_rate, i};
            if (name == "p_" + q) return {value_source::canonical_momentum, i};
        }
        throw user_error(where, "the " + std::string(to_string(form)) + " form does not give '" + name + "'");
    };
    for (std::size_t r = 0; r < scene.record.size(); ++r) {
        const std::string& name = scene.record[r];
        if (name.rfind("body_", 0) == 0) {
            const auto it = f.outputs.find("rotation");
            if (it == f.outputs.end())
                throw user_error(scene.record_where[r], "the " + std::string(to_string(form)) +
                                                            " form does not give '" + name + "'");
            const int row = name.back() - 'x'; // body axis i in space axes = row i of A
            for (int k = 0; k < 3; ++k) {
                program.push_back(it->second.values[static_cast<std::size_t>(3 * row + k)]);
                c.columns.push_back({value_source::compiled, static_cast<int>(program.size() - 1)});
            }
        } else {
            c.columns.push_back(source_of(name, scene.record_where[r]));
        }
    }
    for (const auto& inv : invariants) c.invariants.push_back(source_of(inv.name, scene.where));
    c.outputs = program.size();

    // The record program, lowered like the kernels, and the exported entry points.
    std::vector<program_input> inputs;
    for (std::size_t i = 0; i < f.state.size(); ++i)
        inputs.push_back({f.state[i].symbol, f.state[i].name, "y[" + std::to_string(i) + "]"});
    for (const auto& fp : f.parameters)
        inputs.push_back({fp.symbol, fp.name, "rg_p." + fp.name, fp.specialisable});
    inputs.push_back({f.time, "t", ""});
    const lowered_program lowered = lower(program, inputs);
    const std::vector<bool> used = used_inputs(lowered);
    std::ostringstream shim;
    shim << header.text << "\n// ---- rotgen simulate: entry points for the runtime ----\n"
         << "namespace {\nnamespace rg_model = rotgen::models::" << header.unit << ";\n"
         << "rg_model::params<double> rg_p;\n}\n\nextern \"C\" {\n"
         << "void rotgen_set_parameters(const double* v) {\n";
    for (std::size_t i = 0; i < f.parameters.size(); ++i)
        shim << "    rg_p." << f.parameters[i].name << " = v[" << i << "];\n";
    shim << (f.parameters.empty() ? "    (void)v;\n" : "") << "}\n"
         << "void rotgen_rhs(double t, const double* y, double* dydt) { rg_model::rhs(t, y, dydt, rg_p); }\n"
         << "void rotgen_jacobian(double t, const double* y, double* J) { rg_model::jacobian(t, y, J, rg_p); }\n"
         << "void rotgen_record(double t, const double* y, double* out) {\n"
         << "    using namespace std;\n    (void)t;\n    (void)y;\n    (void)out;\n";
    for (std::size_t i = 0; i < inputs.size(); ++i)
        if (used[i] && !inputs[i].definition.empty())
            shim << "    const double " << inputs[i].name << " = " << inputs[i].definition << ";\n";
    for (const auto& step : lowered.steps)
        shim << "    const double " << step.name << " = " << print_definition(lowered, step.node, "double")
             << ";\n";
    for (std::size_t i = 0; i < lowered.outputs.size(); ++i)
        shim << "    out[" << i << "] = " << print_node(lowered, lowered.outputs[i], "double") << ";\n";
    shim << "}\n}\n";

    c.lib = compile_and_load(shim.str(), header.unit);
    c.sys.n = f.state.size();
    c.sys.f = reinterpret_cast<loaded_system::kernel>(c.lib.symbol("rotgen_rhs"));
    c.sys.jac = reinterpret_cast<loaded_system::kernel>(c.lib.symbol("rotgen_jacobian"));
    c.record = reinterpret_cast<loaded_system::kernel>(c.lib.symbol("rotgen_record"));
    c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return c;
}

// The form's parameters: the scene's values of the model's, and the conserved momenta (reduced).
std::vector<double> form_parameter_values(const scene_spec& scene, const form_expressions& f,
                                          const initial_state& k0) {
    const model_spec& spec = scene.model;
    std::vector<double> values;
    for (const auto& fp : f.parameters) {
        std::optional<double> v;
        for (std::size_t i = 0; i < spec.parameters.size(); ++i)
            if (spec.parameters[i].name == fp.name) v = scene.parameters[i];
        for (int i = 0; i < 3 && !v; ++i)
            if ("p_" + coordinate_names()[i] == fp.name) {
                if (!k0.have_rates)
                    throw user_error(scene.initial_where, "the reduced form needs the initial momenta");
                v = k0.p[i];
            }
        if (!v) throw std::logic_error("simulate: no value for form parameter " + fp.name);
        values.push_back(*v);
    }
    return values;
}

// The state vector of a form from the initial kinematics.
Eigen::VectorXd form_state(const scene_spec& scene, const form_expressions& f, const initial_state& k) {
    const Eigen::Quaterniond quat = quaternion_from_euler(k.q[0], k.q[1], k.q[2]);
    Eigen::VectorXd y(static_cast<Eigen::Index>(f.state.size()));
    for (std::size_t s = 0; s < f.state.size(); ++s) {
        const std::string& name = f.state[s].name;
        std::optional<double> v;
        for (int i = 0; i < 3 && !v; ++i) {
            const std::string& q = coordinate_names()[i];
            if (name == q) v = k.q[i];
            else if (name == "omega" + std::to_string(i + 1)) v = k.omega[i];
            else if (name == q + "_dot" || name == "p_" + q) {
                if (!k.have_rates)
                    throw user_error(scene.initial_where,
                                     "at theta = 0 the " + std::string(to_string(scene.form)) +
                                         " form cannot start from body omega; use form: body");
                v = name == q + "_dot" ? k.qd[i] : k.p[i];
            }
        }
        if (name == "qw") v = quat.w();
        if (name == "qx") v = quat.x();
        if (name == "qy") v = quat.y();
        if (name == "qz") v = quat.z();
        if (!v) throw std::logic_error("simulate: unknown state variable " + name);
        y[static_cast<Eigen::Index>(s)] = *v;
    }
    return y;
}

// Thrown by the observer to leave an Euler-angle run near the singularity.
struct leave_chart {};

// A recorded column or monitored invariant at a sample (t, y) of a form: an output `out` of its
// record program, or in the body form from the quaternion and omega: the Euler angles, their
// rates q_dot = J^{-1} omega (5.30, undefined at theta = 0, pi), p = J^T I omega. `e` caches the
// angles between calls at one sample.
double source_value(const value_source& src, const Eigen::VectorXd& y,
                    const std::vector<double>& out, const Eigen::Matrix3d& inertia,
                    std::optional<euler_angles<double>>& e) {
    if (src.kind == value_source::compiled) return out[static_cast<std::size_t>(src.index)];
    if (!e) e = euler_from_quaternion(Eigen::Quaterniond(y[0], y[1], y[2], y[3]));
    const Eigen::Vector3d w(y[4], y[5], y[6]);
    const double st = std::sin(e->theta), ct = std::cos(e->theta), sp = std::sin(e->psi),
                 cp = std::cos(e->psi);
    if (src.kind == value_source::angle)
        return src.index == 0 ? e->phi : src.index == 1 ? e->theta : e->psi;
    if (src.kind == value_source::euler_rate) {
        const double phi_dot = (w[0] * sp + w[1] * cp) / st; // undefined at theta = 0, pi
        return src.index == 0   ? phi_dot
               : src.index == 1 ? w[0] * cp - w[1] * sp
                                : w[2] - phi_dot * ct;
    }
    const Eigen::Vector3d l = inertia * w; // p = J^T l, J of (5.30)
    return src.index == 0   ? st * sp * l[0] + st * cp * l[1] + ct * l[2]
           : src.index == 1 ? cp * l[0] - sp * l[1]
                            : l[2];
}

void set_parameters(const compiled_form& cf, const std::vector<double>& values) {
    using set_fn = void (*)(const double*);
    reinterpret_cast<set_fn>(cf.lib.symbol("rotgen_set_parameters"))(values.data());
}

// Initial values the parser accepts (each finite) may still overflow double precision in what
// the run computes from them: a rate of 1e300 squares to inf in the energy. Before the run, and
// before any output: the initial kinematics (rates, momenta, omega), the form's state and
// parameters, f(t0, y0), and the energy and conserved momenta at t0 must be finite — as the
// kernels compute them — or the scene's `initial` is the error.
void check_finite_start(const scene_spec& scene, const initial_state& k0, const compiled_form& cf,
                        const Eigen::VectorXd& y, const std::vector<double>& parameters,
                        const std::vector<invariant>& invariants, const Eigen::Matrix3d& inertia) {
    const auto check = [&](const std::string& what, double v, const std::string& in = "") {
        if (std::isfinite(v)) return;
        throw user_error(
            scene.initial_where,
            "initial values too large for double precision: " + what + " = " + format_number(v) +
                in + " at t = " + format_double(scene.t_start) +
                "; give smaller initial rates or momenta, or rescale the model's units");
    };
    const auto& q = coordinate_names();
    if (k0.have_rates)
        for (int i = 0; i < 3; ++i) {
            check(q[i] + "_dot", k0.qd[i]);
            check("p_" + q[i], k0.p[i]);
            check("omega" + std::to_string(i + 1), k0.omega[i]);
        }
    const form_expressions& f = cf.f;
    for (std::size_t i = 0; i < f.state.size(); ++i)
        check(f.state[i].name, y[static_cast<Eigen::Index>(i)]);
    for (std::size_t i = 0; i < f.parameters.size(); ++i)
        check(f.parameters[i].name, parameters[i]);
    Eigen::VectorXd dydt(y.size());
    cf.sys.rhs(scene.t_start, y.data(), dydt.data());
    for (std::size_t i = 0; i < f.rate_names.size(); ++i)
        check(f.rate_names[i], dydt[static_cast<Eigen::Index>(i)], " in f(t0, y0)");
    std::vector<double> out(cf.outputs);
    cf.record(scene.t_start, y.data(), out.data());
    std::optional<euler_angles<double>> e;
    for (std::size_t i = 0; i < invariants.size(); ++i)
        check(invariants[i].name, source_value(cf.invariants[i], y, out, inertia, e));
}

// Without `record:` the scene records phi, theta, psi and energy; the reduced form has no ignored
// angle to record, so the default keeps only what the form gives (an explicit record is checked
// in compile_form, and an angle the form lacks is an error there).
void default_record_follows_form(scene_spec& scene, const derivation& d) {
    if (!scene.record_default || scene.form != form_kind::reduced) return;
    const form_expressions f = build_form(scene.model, d, form_kind::reduced,
                                          lagrangian_strategy::explicit_inverse, false);
    for (std::size_t r = scene.record.size(); r-- > 0;)
        if (!record_expression(f, scene.record[r])) {
            scene.record.erase(scene.record.begin() + static_cast<std::ptrdiff_t>(r));
            scene.record_where.erase(scene.record_where.begin() + static_cast<std::ptrdiff_t>(r));
        }
}

} // namespace

int cmd_simulate(const std::vector<std::string>& args) {
    const simulate_options opt = parse_arguments(args);
    scene_spec scene = load_scene(opt.scene);
    const model_spec& spec = scene.model;

    // Output paths are checked before any work (no partial output, early clear error).
    std::optional<output_file> csv_out;
    if (!opt.csv.empty()) csv_out.emplace(opt.csv);
    if (!opt.plot.empty()) output_file probe(opt.plot);

    const auto t_derive = std::chrono::steady_clock::now();
    const derivation d = derive(spec);
    GiNaC::exmap parameter_values;
    for (std::size_t i = 0; i < spec.parameters.size(); ++i)
        parameter_values[spec.parameters[i].symbol] = float_numeric(scene.parameters[i]);
    Eigen::Matrix3d inertia;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) inertia(i, j) = number(spec.inertia[i][j], parameter_values);

    // Gimbal lock: the Lagrangian and Hamiltonian forms continue in the body form (quaternion
    // and omega, no singularity) when |sin(theta)| falls below this at a sample, or when their
    // integration fails — provided the model's body form does not itself go through the chart.
    const double switch_below = 0.1;
    const bool can_switch =
        scene.switch_chart &&
        (scene.form == form_kind::lagrangian || scene.form == form_kind::hamiltonian) &&
        !build_form(spec, d, form_kind::body, lagrangian_strategy::explicit_inverse, true).uses_euler_chart;
    const bool euler_form = scene.form != form_kind::body;
    bool start_in_body = false;
    const double sin_theta0 = std::abs(std::sin(scene.angles[1]));
    if (euler_form && sin_theta0 < 1e-10 && !can_switch)
        throw user_error(scene.initial_where,
                         "initial theta = " + format_number(scene.angles[1]) +
                             " is the gimbal-lock singularity of the Euler-angle forms (sin theta = "
                             "0); use form: body" +
                             (scene.form == form_kind::reduced || !scene.switch_chart
                                  ? ""
                                  : " (this model's body form goes through the Euler-angle chart too)"));
    if (euler_form && can_switch && sin_theta0 < switch_below) start_in_body = true;
    const initial_state k0 = initial_kinematics(scene, d, parameter_values);
    const double derive_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t_derive).count();

    // The invariants to monitor: the energy, and every momentum the derivation found conserved.
    std::vector<invariant> invariants{{"energy", !spec.has_damping && !spec.has_torque}};
    for (int i : d.cyclic)
        if (scene.form != form_kind::reduced) invariants.push_back({"p_" + coordinate_names()[i], true});

    default_record_follows_form(scene, d);

    // The body form keeps the quaternion only when something needs the orientation (a potential,
    // a recorded angle or body axis, a switch of chart); a free body is then integrated as omega.
    bool orientation = can_switch;
    for (const auto& name : scene.record)
        orientation = orientation || name == "phi" || name == "theta" || name == "psi" ||
                      name.rfind("body_", 0) == 0 || name.find("_dot") != std::string::npos ||
                      name.rfind("p_", 0) == 0;
    if (scene.form == form_kind::body && !orientation && invariants.size() > 1) orientation = true;
    // The stamp in the compiled source names no path, so the same kernels are compiled once,
    // whatever scene file asks for them.
    const std::string command = "rotgen simulate (kernels of model '" + spec.name + "')";
    std::vector<compiled_form> forms;
    forms.push_back(compile_form(scene, d, start_in_body ? form_kind::body : scene.form, orientation,
                                 invariants, command));
    std::vector<std::string> columns;
    for (const auto& name : scene.record)
        for (const auto& c : record_columns(name)) columns.push_back(c);

    // Integrate, sampling at the requested times by dense output, segment by segment.
    const integrator_spec& ig = scene.integrator;
    auto method = make_method<double>(ig.method, ig.rtol, ig.atol, ig.fixed_step() ? ig.step : 0.0);
    if (!method) throw std::logic_error("simulate: unknown method " + ig.method);
    std::visit([&](auto& m) { m.max_steps = ig.max_steps; }, *method);
    if (auto* r = std::get_if<rodas4<double>>(&*method)) r->autonomous = !spec.has_torque;
    std::vector<double> times(static_cast<std::size_t>(scene.samples));
    for (std::size_t i = 0; i < times.size(); ++i)
        times[i] = i + 1 == times.size()
                       ? scene.t_end
                       : scene.t_start + (scene.t_end - scene.t_start) * double(i) / double(times.size() - 1);

    struct sample {
        double t;
        Eigen::VectorXd y;
        std::size_t form; // index into forms
    };
    std::vector<sample> samples;
    samples.reserve(times.size());
    step_stats stats;
    integration_result<double> result;
    double run_seconds = 0;
    std::string chart_note = start_in_body ? "started in the body form (initial |sin theta| = " +
                                                 short_number(sin_theta0) + " < " +
                                                 short_number(switch_below) + ")"
                                           : "";
    Eigen::VectorXd y = form_state(scene, forms[0].f, k0);
    std::vector<double> parameters = form_parameter_values(scene, forms[0].f, k0);
    set_parameters(forms[0], parameters);
    check_finite_start(scene, k0, forms[0], y, parameters, invariants, inertia);
    double t_from = scene.t_start;
    std::size_t next_sample = 0;
    while (true) {
        compiled_form& cf = forms.back();
        set_parameters(cf, parameters);
        const bool in_euler_chart = cf.form == form_kind::lagrangian || cf.form == form_kind::hamiltonian;
        const std::vector<double> segment_times(times.begin() + static_cast<std::ptrdiff_t>(next_sample), times.end());
        bool leaving = false;
        const auto t_run = std::chrono::steady_clock::now();
        try {
            result = integrate(cf.sys, *method, t_from, y, segment_times,
                               [&](double t, const Eigen::VectorXd& yt) {
                                   samples.push_back({t, yt, forms.size() - 1});
                                   if (can_switch && in_euler_chart && std::abs(std::sin(yt[1])) < switch_below &&
                                       samples.size() > 1 && t < scene.t_end)
                                       throw leave_chart{};
                               });
        } catch (const leave_chart&) {
            leaving = true;
        }
        run_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t_run).count();
        if (!leaving) {
            stats.steps += result.stats.steps, stats.accepted += result.stats.accepted;
            stats.rejected += result.stats.rejected, stats.rhs_evals += result.stats.rhs_evals;
            stats.jac_evals += result.stats.jac_evals, stats.factorisations += result.stats.factorisations;
        }
        const bool failed = !leaving && !result.ok();
        if (!(can_switch && in_euler_chart && (leaving || failed) && !samples.empty() &&
              samples.back().t < scene.t_end))
            break;
        // Continue from the last sample in the body form: omega = J q_dot (5.30).
        const sample& last = samples.back();
        initial_state k;
        for (int i = 0; i < 3; ++i) k.q[i] = last.y[i];
        Eigen::VectorXd dydt(last.y.size());
        cf.sys.rhs(last.t, last.y.data(), dydt.data());
        for (int i = 0; i < 3; ++i) k.qd[i] = dydt[i];
        const double st = std::sin(k.q[1]), ct = std::cos(k.q[1]), sp = std::sin(k.q[2]), cp = std::cos(k.q[2]);
        k.omega = {k.qd[0] * st * sp + k.qd[1] * cp, k.qd[0] * st * cp - k.qd[1] * sp, k.qd[0] * ct + k.qd[2]};
        chart_note = "switched to the body form at t = " + short_number(last.t) + " (|sin theta| = " +
                     short_number(std::abs(st)) + (leaving ? " < " + short_number(switch_below) + ")"
                                                          : "; the Euler-angle run failed: " + result.message + ")");
        forms.push_back(compile_form(scene, d, form_kind::body, true, invariants, command));
        y = form_state(scene, forms.back().f, k);
        parameters = form_parameter_values(scene, forms.back().f, k);
        t_from = last.t;
        next_sample = samples.size();
    }

    // Records and invariants at every sample, each by the form that integrated it.
    std::vector<std::vector<double>> rows;
    std::vector<double> first(invariants.size()), drift(invariants.size(), 0.0);
    for (std::size_t k = 0; k < samples.size(); ++k) {
        const compiled_form& cf = forms[samples[k].form];
        const Eigen::VectorXd& ys = samples[k].y;
        std::vector<double> out(cf.outputs);
        cf.record(samples[k].t, ys.data(), out.data());
        std::optional<euler_angles<double>> e;
        const auto value = [&](const value_source& src) {
            return source_value(src, ys, out, inertia, e);
        };
        std::vector<double> row{samples[k].t};
        for (const auto& src : cf.columns) row.push_back(value(src));
        rows.push_back(std::move(row));
        for (std::size_t i = 0; i < invariants.size(); ++i) {
            const double v = value(cf.invariants[i]);
            if (k == 0) first[i] = v;
            drift[i] = std::max(drift[i], std::abs(v - first[i]));
        }
    }

    if (csv_out) {
        std::ostream& os = csv_out->stream();
        os << "t";
        for (const auto& c : columns) os << "," << c;
        os << "\n";
        for (const auto& row : rows) {
            for (std::size_t i = 0; i < row.size(); ++i) os << (i ? "," : "") << format_number(row[i]);
            os << "\n";
        }
        csv_out->commit();
    }

    // The summary.
    double compile_seconds = 0;
    bool all_cached = true;
    for (const auto& cf : forms) compile_seconds += cf.seconds, all_cached = all_cached && cf.lib.was_cached();
    std::cout << "rotgen simulate " << opt.scene << "\n"
              << "  model   " << spec.name << " (" << spec.file << "), " << to_string(scene.form)
              << " form, " << forms[0].f.state.size() << " states\n";
    if (!chart_note.empty()) std::cout << "  chart   " << chart_note << "\n";
    std::cout << "  method  " << ig.method;
    if (ig.fixed_step()) std::cout << " step " << format_double(ig.step);
    else std::cout << " rtol " << format_double(ig.rtol) << " atol " << format_double(ig.atol);
    std::cout << ", t " << format_double(scene.t_start) << " .. "
              << format_double(samples.empty() ? scene.t_start : samples.back().t) << "\n"
              << "  steps   " << stats.accepted << " accepted, " << stats.rejected << " rejected; "
              << stats.rhs_evals << " RHS and " << stats.jac_evals << " Jacobian evaluations, "
              << stats.factorisations << " factorisations\n"
              << "  time    " << short_number(run_seconds * 1e3) << " ms integrating; "
              << short_number(derive_seconds) << " s deriving, " << short_number(compile_seconds) << " s "
              << (all_cached ? "emitting and loading the cached kernels" : "emitting and compiling the kernels") << "\n";
    for (std::size_t i = 0; i < invariants.size(); ++i) {
        const double scale = std::max(std::abs(first[i]), 1e-300);
        std::cout << "  " << (invariants[i].conserved ? "drift   " : "change  ") << invariants[i].name
                  << ": max |" << invariants[i].name << "(t) - " << invariants[i].name
                  << "(0)| = " << short_number(drift[i]) << " (relative " << short_number(drift[i] / scale) << ")"
                  << (invariants[i].conserved ? "" : ", not conserved: the model is damped or driven") << "\n";
    }
    std::size_t non_finite = 0;
    for (const auto& row : rows)
        for (double v : row) non_finite += std::isfinite(v) ? 0 : 1;
    if (non_finite > 0)
        std::cout << "  note    " << non_finite << " recorded values are not finite (inf or nan): "
                  << "Euler-angle rates are undefined at theta = 0 and pi\n";
    if (csv_out) std::cout << "  wrote   " << opt.csv << " (" << rows.size() << " samples)\n";
    if (!opt.plot.empty()) {
        std::string csv_for_plot = opt.csv;
        std::optional<output_file> scratch;
        if (csv_for_plot.empty()) { // plot from a scratch CSV beside the PNG
            scratch.emplace(opt.plot + ".csv");
            std::ostream& os = scratch->stream();
            for (const auto& row : rows) {
                for (std::size_t i = 0; i < row.size(); ++i) os << (i ? "," : "") << format_number(row[i]);
                os << "\n";
            }
            os.flush();
            csv_for_plot = scratch->temporary();
        }
        double energy0 = 0;
        for (std::size_t i = 0; i < columns.size(); ++i)
            if (columns[i] == "energy" && !rows.empty()) energy0 = rows[0][i + 1];
        plot(opt.plot, csv_for_plot, scene.record,
             spec.name + " (" + to_string(scene.form) + " form, " + ig.method + ")", energy0);
        std::cout << "  wrote   " << opt.plot << "\n";
    }
    if (!result.ok())
        throw user_error(scene.integrator_where,
                         "the integration stopped: " + result.message +
                             (csv_out ? " (the samples up to there were written)" : ""));
    return 0;
}

} // namespace rotgen
