// rotgen simulate SCENE.yaml [-o out.csv] [--plot out.png]
//
// derive -> emit the scene's form -> compile it (cached shared object) -> load -> integrate with the
// runtime -> write the recorded quantities (CSV, header `t,<names>`) -> plot (gnuplot).
// Angles are z-x-z Euler angles (passive A = Az(psi) Ax(theta) Az(phi), 5.25), omega in body axes.
#include "commands.hpp"
#include "derive.hpp"
#include "emit.hpp"
#include "error.hpp"
#include "forms.hpp"
#include "jit.hpp"
#include "lower.hpp"
#include "print.hpp"
#include "scene.hpp"
#include "symbols.hpp"

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
    for (int i = 0; i < 3; ++i) at[s.q[i]] = k.q[i];
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
        for (int i = 0; i < 3; ++i) at[s.qd[i]] = k.qd[i];
        for (int i = 0; i < 3; ++i) {
            k.p[i] = number(d.momenta[i], at);
            if (scene.initial != initial_kind::omega) k.omega[i] = number(d.omega[i], at);
        }
    }
    return k;
}

// Where a recorded column comes from.
struct column_source {
    enum kind_t { compiled, angle_of_quaternion } kind;
    int index; // compiled: output of the record program; angle: 0, 1, 2
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

std::string shell_quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
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

} // namespace

int cmd_simulate(const std::vector<std::string>& args) {
    const simulate_options opt = parse_arguments(args);
    const scene_spec scene = load_scene(opt.scene);
    const model_spec& spec = scene.model;

    // Output paths are checked before any work (no partial output, early clear error).
    std::optional<output_file> csv_out;
    if (!opt.csv.empty()) csv_out.emplace(opt.csv);
    if (!opt.plot.empty()) output_file probe(opt.plot);

    const bool euler_form = scene.form != form_kind::body;
    if (euler_form && std::abs(std::sin(scene.angles[1])) < 1e-10)
        throw user_error(scene.initial_where,
                         "initial theta = " + format_number(scene.angles[1]) +
                             " is the gimbal-lock singularity of the Euler-angle forms (sin theta = "
                             "0); use form: body");

    const auto t_derive = std::chrono::steady_clock::now();
    const derivation d = derive(spec);
    // The body form keeps the quaternion only when something needs the orientation (a potential,
    // or a recorded angle or body axis); a free body is then integrated as omega alone.
    bool orientation = false;
    for (const auto& name : scene.record)
        orientation = orientation || name == "phi" || name == "theta" || name == "psi" ||
                      name.rfind("body_", 0) == 0;
    const form_expressions f =
        build_form(spec, d, scene.form, lagrangian_strategy::explicit_inverse, orientation);
    emit_options eo;
    eo.form = scene.form;
    eo.outputs = {"rhs", "jacobian"};
    if (scene.form == form_kind::body && orientation) eo.outputs.push_back("rotation");
    eo.command = "rotgen simulate " + opt.scene;
    const emitted_header header = emit_header(spec, d, eo);
    // The compiled kernels and the state built here must agree on the layout.
    const std::string size_decl = "state_size = " + std::to_string(f.state.size()) + ";";
    if (header.text.find(size_decl) == std::string::npos)
        throw std::logic_error("simulate: the emitted " + header.unit + " does not have " + size_decl);

    // The parameters' values: the scene's, and the conserved momenta of a reduced form.
    GiNaC::exmap parameter_values;
    for (std::size_t i = 0; i < spec.parameters.size(); ++i)
        parameter_values[spec.parameters[i].symbol] = scene.parameters[i];
    const initial_state k0 = initial_kinematics(scene, d, parameter_values);
    std::vector<double> form_parameters;
    for (const auto& fp : f.parameters) {
        double v = 0;
        bool found = false;
        for (std::size_t i = 0; i < spec.parameters.size(); ++i)
            if (spec.parameters[i].name == fp.name) v = scene.parameters[i], found = true;
        for (int i = 0; i < 3 && !found; ++i)
            if ("p_" + coordinate_names()[i] == fp.name) {
                if (!k0.have_rates)
                    throw user_error(scene.initial_where, "the reduced form needs the initial momenta");
                v = k0.p[i], found = true;
            }
        if (!found) throw std::logic_error("simulate: no value for form parameter " + fp.name);
        form_parameters.push_back(v);
    }

    // The initial state vector of the form.
    const Eigen::Quaterniond quat = quaternion_from_euler(k0.q[0], k0.q[1], k0.q[2]);
    const auto state_value = [&](const std::string& name) -> double {
        for (int i = 0; i < 3; ++i) {
            const std::string& q = coordinate_names()[i];
            if (name == q) return k0.q[i];
            if (name == q + "_dot" || name == "p_" + q) {
                if (!k0.have_rates)
                    throw user_error(scene.initial_where,
                                     "at theta = 0 the " + std::string(to_string(scene.form)) +
                                         " form cannot start from body omega; use form: body");
                return name == q + "_dot" ? k0.qd[i] : k0.p[i];
            }
            if (name == "omega" + std::to_string(i + 1)) return k0.omega[i];
        }
        if (name == "qw") return quat.w();
        if (name == "qx") return quat.x();
        if (name == "qy") return quat.y();
        if (name == "qz") return quat.z();
        throw std::logic_error("simulate: unknown state variable " + name);
    };
    const std::size_t n = f.state.size();
    Eigen::VectorXd y(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) y[static_cast<Eigen::Index>(i)] = state_value(f.state[i].name);

    // What to record, and the invariants to monitor.
    std::vector<ex> program_outputs;
    std::vector<std::string> columns;
    std::vector<column_source> sources;
    for (std::size_t r = 0; r < scene.record.size(); ++r) {
        const std::string& name = scene.record[r];
        if (name.rfind("body_", 0) == 0) {
            const auto it = f.outputs.find("rotation");
            if (it == f.outputs.end())
                throw user_error(scene.record_where[r], "the " + std::string(to_string(scene.form)) +
                                                            " form does not give '" + name + "'");
            const int row = name.back() - 'x'; // body axis i in space axes = row i of A
            for (int c = 0; c < 3; ++c) {
                sources.push_back({column_source::compiled, static_cast<int>(program_outputs.size())});
                program_outputs.push_back(it->second.values[static_cast<std::size_t>(3 * row + c)]);
            }
        } else if (auto e = record_expression(f, name)) {
            sources.push_back({column_source::compiled, static_cast<int>(program_outputs.size())});
            program_outputs.push_back(*e);
        } else if (scene.form == form_kind::body && (name == "phi" || name == "theta" || name == "psi")) {
            sources.push_back({column_source::angle_of_quaternion, name == "phi" ? 0 : name == "theta" ? 1 : 2});
        } else {
            throw user_error(scene.record_where[r], "the " + std::string(to_string(scene.form)) +
                                                        " form does not give '" + name + "'");
        }
        for (const auto& c : record_columns(name)) columns.push_back(c);
    }
    struct invariant {
        std::string name;
        int output;
        bool conserved;
    };
    std::vector<invariant> invariants;
    const bool conservative = !spec.has_damping && !spec.has_torque;
    if (auto e = record_expression(f, "energy")) {
        invariants.push_back({"energy", static_cast<int>(program_outputs.size()), conservative});
        program_outputs.push_back(*e);
    }
    for (int i : d.cyclic) {
        const std::string name = "p_" + coordinate_names()[i];
        if (auto e = record_expression(f, name)) {
            invariants.push_back({name, static_cast<int>(program_outputs.size()), true});
            program_outputs.push_back(*e);
        }
    }

    // The record program, lowered like the kernels, and the exported entry points.
    std::vector<program_input> inputs;
    for (std::size_t i = 0; i < n; ++i)
        inputs.push_back({f.state[i].symbol, f.state[i].name, "y[" + std::to_string(i) + "]"});
    for (const auto& fp : f.parameters) inputs.push_back({fp.symbol, fp.name, "rg_p." + fp.name});
    inputs.push_back({f.time, "t", ""});
    const lowered_program program = lower(program_outputs, inputs);
    const std::vector<bool> used = used_inputs(program);
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
         << "    using namespace std;\n    (void)t;\n    (void)y;\n";
    for (std::size_t i = 0; i < inputs.size(); ++i)
        if (used[i] && !inputs[i].definition.empty())
            shim << "    const double " << inputs[i].name << " = " << inputs[i].definition << ";\n";
    for (const auto& step : program.steps)
        shim << "    const double " << step.name << " = " << print_definition(program, step.node, "double")
             << ";\n";
    for (std::size_t i = 0; i < program.outputs.size(); ++i)
        shim << "    out[" << i << "] = " << print_node(program, program.outputs[i], "double") << ";\n";
    shim << "}\n}\n";
    const double derive_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t_derive).count();

    const auto t_compile = std::chrono::steady_clock::now();
    const loaded_library lib = compile_and_load(shim.str(), header.unit);
    const double compile_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t_compile).count();
    using set_fn = void (*)(const double*);
    reinterpret_cast<set_fn>(lib.symbol("rotgen_set_parameters"))(form_parameters.data());
    loaded_system sys;
    sys.n = n;
    sys.f = reinterpret_cast<loaded_system::kernel>(lib.symbol("rotgen_rhs"));
    sys.jac = reinterpret_cast<loaded_system::kernel>(lib.symbol("rotgen_jacobian"));
    const auto record_fn = reinterpret_cast<loaded_system::kernel>(lib.symbol("rotgen_record"));

    // Integrate, sampling at the requested times by dense output.
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
    std::vector<double> sample_t;
    std::vector<Eigen::VectorXd> sample_y;
    sample_t.reserve(times.size());
    sample_y.reserve(times.size());
    const auto t_run = std::chrono::steady_clock::now();
    const integration_result<double> result =
        integrate(sys, *method, scene.t_start, y, times, [&](double t, const Eigen::VectorXd& yt) {
            sample_t.push_back(t);
            sample_y.push_back(yt);
        });
    const double run_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t_run).count();

    // Records and invariants at every sample.
    std::vector<double> out(program_outputs.size());
    std::vector<double> first(invariants.size()), drift(invariants.size(), 0.0);
    std::vector<std::vector<double>> rows;
    for (std::size_t k = 0; k < sample_t.size(); ++k) {
        record_fn(sample_t[k], sample_y[k].data(), out.data());
        std::vector<double> row{sample_t[k]};
        std::optional<euler_angles<double>> angles;
        for (const auto& src : sources) {
            if (src.kind == column_source::compiled) {
                row.push_back(out[static_cast<std::size_t>(src.index)]);
            } else {
                if (!angles) {
                    const Eigen::Quaterniond q(sample_y[k][0], sample_y[k][1], sample_y[k][2], sample_y[k][3]);
                    angles = euler_from_quaternion(q);
                }
                row.push_back(src.index == 0 ? angles->phi : src.index == 1 ? angles->theta : angles->psi);
            }
        }
        rows.push_back(std::move(row));
        for (std::size_t i = 0; i < invariants.size(); ++i) {
            const double v = out[static_cast<std::size_t>(invariants[i].output)];
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
    const step_stats& st = result.stats;
    std::cout << "rotgen simulate " << opt.scene << "\n"
              << "  model   " << spec.name << " (" << spec.file << "), " << to_string(scene.form)
              << " form, " << n << " states\n"
              << "  method  " << ig.method;
    if (ig.fixed_step()) std::cout << " step " << format_double(ig.step);
    else std::cout << " rtol " << format_double(ig.rtol) << " atol " << format_double(ig.atol);
    std::cout << ", t " << format_double(scene.t_start) << " .. " << format_double(result.t) << "\n"
              << "  steps   " << st.accepted << " accepted, " << st.rejected << " rejected; "
              << st.rhs_evals << " RHS and " << st.jac_evals << " Jacobian evaluations, "
              << st.factorisations << " factorisations\n"
              << "  time    " << short_number(run_seconds * 1e3) << " ms integrating; "
              << short_number(derive_seconds) << " s deriving, "
              << short_number(compile_seconds) << " s "
              << (lib.was_cached() ? "loading the cached kernels" : "compiling the kernels") << "\n";
    for (std::size_t i = 0; i < invariants.size(); ++i) {
        const double scale = std::max(std::abs(first[i]), 1e-300);
        std::cout << "  " << (invariants[i].conserved ? "drift   " : "change  ") << invariants[i].name
                  << ": max |" << invariants[i].name << "(t) - " << invariants[i].name
                  << "(0)| = " << short_number(drift[i]) << " (relative "
                  << short_number(drift[i] / scale) << ")"
                  << (invariants[i].conserved ? "" : ", not conserved: the model is damped or driven")
                  << "\n";
    }
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
