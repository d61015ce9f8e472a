#include "run/kernels.hpp"

#include "run/event_kernels.hpp"

#include "emit/emit.hpp"
#include "emit/taylor.hpp"
#include "expr/symbols.hpp"
#include "lower/lower.hpp"
#include "run/angle_chart.hpp"
#include "run/records.hpp"
#include "run/sensitivity_start.hpp"
#include "run/source_value.hpp"
#include "run/variational.hpp"
#include "support/error.hpp"

#include <algorithm>
#include <sstream>

namespace rotgen {

namespace {

using GiNaC::ex;

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

// Where each recorded column and invariant comes from: the form's own expressions where it has
// them (appended to `program`); in the body form the Euler-angle quantities are computed from the
// quaternion and omega at each sample.
class source_finder {
  public:
    source_finder(const scene_spec& scene, const compiled_form& c, bool orientation,
                  std::vector<ex>& program)
        : m_spec(scene.model), m_c(c), m_body_with_angles(c.form == form_kind::body && orientation),
          m_sensitive(scene.sensitivities.active()), m_program(program) {}

    value_source operator()(const std::string& name, const source_location& where) {
        if (auto e = record_expression(m_c.f, name)) return compiled(*e);
        if (auto e = derived_record(m_spec, m_c.f, name)) return compiled(*e);
        for (int i = 0; i < 4; ++i)
            if (name == "q" + std::to_string(i)) {
                if (m_body_with_angles) return {value_source::quaternion_of_state, i};
                if (m_c.form == form_kind::lagrangian || m_c.form == form_kind::hamiltonian)
                    return {value_source::quaternion_of_angles, i};
            }
        for (int i = 0; i < 3 && m_body_with_angles; ++i) {
            const std::string& q = m_spec.angles.names[i];
            if (name == q) return {value_source::angle, i};
            if (name == q + "_dot") return {value_source::euler_rate, i};
            if (name == "p_" + q) return canonical_momentum(i);
        }
        throw user_error(where, "the " + std::string(to_string(m_c.form)) +
                                    " form does not give '" + name + "'");
    }

    // body_x, body_y, body_z: body axis i in space axes, row i of A (three columns).
    void body_axis(const std::string& name, const source_location& where,
                   std::vector<value_source>& out) {
        const auto it = m_c.f.outputs.find("rotation");
        if (it == m_c.f.outputs.end())
            throw user_error(where, "the " + std::string(to_string(m_c.form)) +
                                        " form does not give '" + name + "'");
        const int row = name.back() - 'x';
        for (int k = 0; k < 3; ++k)
            out.push_back(compiled(it->second.values[static_cast<std::size_t>(3 * row + k)]));
    }

  private:
    // p = J^T l, l = I omega, or for a gyrostat the total I omega + h, from the record program
    // (with sensitivities: its derivatives by the parameters come with it).
    value_source canonical_momentum(int i) {
        value_source v{value_source::canonical_momentum, i};
        if (m_spec.wheels.empty() && !m_sensitive) return v;
        const auto& Q = symbols().omega;
        const auto l = gyrostat_momentum(m_spec, {Q[0], Q[1], Q[2]});
        v.momentum = compiled(l[0]).index;
        compiled(l[1]), compiled(l[2]);
        return v;
    }
    value_source compiled(const ex& e) {
        m_program.push_back(e);
        return {value_source::compiled, static_cast<int>(m_program.size() - 1)};
    }
    const model_spec& m_spec;
    const compiled_form& m_c;
    bool m_body_with_angles, m_sensitive;
    std::vector<ex>& m_program;
};

// The program computing the recorded columns and invariants; fills c.columns and c.invariants.
std::vector<ex> record_program(const scene_spec& scene, compiled_form& c, bool orientation,
                               const std::vector<invariant>& invariants) {
    std::vector<ex> program;
    source_finder source(scene, c, orientation, program);
    for (std::size_t r = 0; r < scene.record.size(); ++r) {
        const std::string& name = scene.record[r];
        if (name.rfind("body_", 0) == 0)
            source.body_axis(name, scene.record_where[r], c.columns);
        else
            c.columns.push_back(source(name, scene.record_where[r]));
    }
    for (const auto& inv : invariants)
        c.invariants.push_back(source(inv.name, scene.where));
    c.outputs = program.size();
    return program;
}

// The body of a function (t, y, out) that computes `program` into out[0..]: the inputs it uses
// (the state y, the parameters rg_p, t), the CSE steps, the outputs.
void print_body(std::ostream& shim, const form_expressions& f, const std::vector<ex>& program) {
    std::vector<program_input> inputs;
    for (std::size_t i = 0; i < f.state.size(); ++i)
        inputs.push_back({f.state[i].symbol, f.state[i].name, "y[" + std::to_string(i) + "]"});
    for (const auto& fp : f.parameters)
        inputs.push_back({fp.symbol, fp.name, "rg_p." + fp.name, fp.specialisable});
    inputs.push_back({f.time, "t", ""});
    const lowered_program lowered = lower(program, inputs);
    const std::vector<bool> used = used_inputs(lowered);
    shim << "    using namespace std;\n    (void)t;\n    (void)y;\n    (void)out;\n";
    for (std::size_t i = 0; i < inputs.size(); ++i)
        if (used[i] && !inputs[i].definition.empty())
            shim << "    const double " << inputs[i].name << " = " << inputs[i].definition << ";\n";
    for (const auto& step : lowered.steps)
        shim << "    const double " << step.name << " = "
             << print_definition(lowered, step.node, "double") << ";\n";
    for (std::size_t i = 0; i < lowered.outputs.size(); ++i)
        shim << "    out[" << i << "] = " << print_node(lowered, lowered.outputs[i], "double")
             << ";\n";
}

// With sensitivities: rotgen_record_jacobian, the record program's outputs differentiated by the
// state, then by the parameters of the form (the model's, and the reduced form's cyclic momenta;
// row-major outputs x (n + P)); and rotgen_event_jacobian_<i>, event i's g by (y, P, t): GiNaC's
// derivatives, exact. (d f/d P is in rotgen_variational, variational.hpp.)
std::vector<std::pair<std::string, std::vector<ex>>>
sensitivity_programs(const scene_spec& scene, const form_expressions& f,
                     const std::vector<ex>& program, const std::vector<ex>& events) {
    if (!scene.sensitivities.active()) return {};
    std::vector<ex> variables;
    for (const auto& s : f.state)
        variables.push_back(s.symbol);
    for (const auto& p : f.parameters)
        variables.push_back(p.symbol);
    const auto by_variables = [&](const std::vector<ex>& outputs, bool time) {
        std::vector<ex> d;
        for (const ex& out : outputs) {
            for (const ex& v : variables)
                d.push_back(out.diff(GiNaC::ex_to<GiNaC::symbol>(v)));
            if (time) d.push_back(out.diff(GiNaC::ex_to<GiNaC::symbol>(f.time)));
        }
        return d;
    };
    std::vector<std::pair<std::string, std::vector<ex>>> more{
        {"rotgen_record_jacobian", by_variables(program, false)}};
    for (std::size_t e = 0; e < events.size(); ++e)
        more.emplace_back("rotgen_event_jacobian_" + std::to_string(e),
                          by_variables({events[e]}, true));
    return more;
}

// The translation unit compiled for the runtime: the header and extern "C" entry points
// rotgen_rhs, rotgen_jacobian, rotgen_record, and rotgen_event_<i> per scene event (each its own
// function: a run evaluates one event without the others), and with `taylor` rotgen_taylor_series
// and rotgen_taylor; each given the parameter values `v`
// (in the form's parameter order) with every call: the compiled object keeps no state, so members
// of an ensemble run its kernels concurrently with their own values.
std::string entry_points(const form_expressions& f, const std::string& unit,
                         const std::vector<ex>& program, const std::vector<ex>& events,
                         const std::string& taylor, const std::vector<std::string>& constants,
                         const std::vector<std::pair<std::string, std::vector<ex>>>& more) {
    std::ostringstream shim;
    shim << "\n// ---- rotgen run: entry points for the runtime ----\n"
         << "namespace {\nnamespace rg_model = rotgen::models::" << unit << ";\n";
    // params from v; prepared from w = (v, the constants), rotgen_prepare
    std::vector<std::string> members;
    for (const auto& p : f.parameters)
        members.push_back(p.name);
    members.insert(members.end(), constants.begin(), constants.end());
    for (const bool prepared : {false, true}) {
        const std::size_t count = prepared ? members.size() : f.parameters.size();
        const std::string type = prepared ? "prepared" : "params";
        shim << "rg_model::" << type << "<double> rg_" << type << "(const double* v) {\n"
             << "    rg_model::" << type << "<double> p;\n";
        for (std::size_t i = 0; i < count; ++i)
            shim << "    p." << members[i] << " = v[" << i << "];\n";
        shim << (count == 0 ? "    (void)v;\n" : "") << "    return p;\n}\n";
    }
    shim << "}\n\nextern \"C\" {\n"
         << "void rotgen_prepare(const double* v, double* w) {\n"
         << "    const rg_model::prepared<double> p = rg_model::prepare(rg_params(v));\n";
    for (std::size_t i = 0; i < members.size(); ++i)
        shim << "    w[" << i << "] = p." << members[i] << ";\n";
    shim << (members.empty() ? "    (void)p;\n    (void)w;\n" : "") << "}\n"
         << "void rotgen_rhs(const double* w, double t, const double* y, double* dydt) {\n"
         << "    rg_model::rhs(t, y, dydt, rg_prepared(w));\n}\n"
         << "void rotgen_jacobian(const double* w, double t, const double* y, double* J) {\n"
         << "    rg_model::jacobian(t, y, J, rg_prepared(w));\n}\n";
    if (!taylor.empty())
        shim << "unsigned long rotgen_taylor_series() { return rg_model::taylor_series; }\n"
             << "void rotgen_taylor(const double* v, double t, double* c, int order) {\n"
             << "    rg_model::" << taylor << "(t, c, order, rg_params(v));\n}\n";
    // the record program and each event: rg_p from v, then the program's body
    const auto function = [&](const std::string& name, const std::vector<ex>& outputs) {
        shim << "void " << name << "(const double* v, double t, const double* y, double* out) {\n"
             << "    const rg_model::params<double> rg_p = rg_params(v);\n    (void)rg_p;\n";
        print_body(shim, f, outputs);
        shim << "}\n";
    };
    function("rotgen_record", program);
    for (std::size_t e = 0; e < events.size(); ++e)
        function("rotgen_event_" + std::to_string(e), {events[e]});
    for (const auto& [name, outputs] : more)
        function(name, outputs);
    shim << "}\n";
    return shim.str();
}

// The Taylor coefficients of (y, S) for a Taylor run with sensitivities
// (run/taylor_sensitivity.hpp), appended to the unit; `forcing` says what its v holds.
std::string augmented_taylor(const scene_spec& scene, const form_expressions& f,
                             const std::string& unit, augmented_forcing& forcing,
                             stage_timings& timings) {
    return timings.time("lower", "taylor sensitivities", [&] {
        const augmented_system a = augmented_rates(scene, f);
        forcing = a.forcing;
        try {
            return taylor_sensitivity_source(a, unit, f.parameters.size());
        } catch (const taylor_unsupported& e) {
            throw user_error(scene.integrator_where, taylor_refusal(scene.model, e));
        }
    });
}

} // namespace

bool form_gives(const form_expressions& f, const std::string& name) {
    return record_expression(f, name).has_value();
}

std::optional<GiNaC::ex> form_value(const form_expressions& f, const std::string& name) {
    return record_expression(f, name);
}

event_direction direction_of(const event_spec& e) {
    return e.direction > 0   ? event_direction::rising
           : e.direction < 0 ? event_direction::falling
                             : event_direction::both;
}

std::string taylor_refusal(const model_spec& spec, const taylor_unsupported& e) {
    return "integrator taylor cannot run model '" + spec.name + "': " + e.what() +
           "; use dop853, dopri5, rk4, implicit_midpoint or rosenbrock";
}

std::string taylor_call(const integrator_spec& integrator) {
    std::vector<int> orders;
    for (const double tol : {integrator.rtol, integrator.atol})
        if (tol > 0) orders.push_back(taylor<double>::order_for(tol));
    std::sort(orders.begin(), orders.end());
    orders.erase(std::unique(orders.begin(), orders.end()), orders.end());
    std::string call = "taylor_specialised<";
    for (std::size_t i = 0; i < orders.size(); ++i)
        call += (i ? ", " : "") + std::to_string(orders[i]);
    return call + ">";
}

compiled_form compile_form(const scene_spec& scene, form_expressions f, bool orientation,
                           const std::vector<invariant>& invariants, const std::string& command,
                           stage_timings& timings) {
    const model_spec& spec = scene.model;
    compiled_form c;
    c.form = f.form;
    c.f = std::move(f);
    kernel_request request;
    request.outputs = {"rhs", "jacobian"};
    if (c.form == form_kind::body && orientation) request.outputs.push_back("rotation");
    const bool taylor = scene.integrator.method == "taylor";
    if (taylor) request.outputs.push_back("taylor");
    const lowered_form lowered =
        timings.time("lower", to_string(c.form), [&] { return lower_form(spec, c.f, request); });
    const emitted_header header = timings.time("emit", to_string(c.form), [&] {
        try {
            return emit_header(spec, lowered, {command, ""});
        } catch (const taylor_unsupported& e) {
            throw user_error(scene.integrator_where, taylor_refusal(spec, e));
        }
    });
    // The compiled kernels and the state built here must agree on the layout.
    const std::string size_decl = "state_size = " + std::to_string(c.f.state.size()) + ";";
    if (header.text.find(size_decl) == std::string::npos)
        throw std::logic_error("run: the emitted " + header.unit + " does not have " + size_decl);
    const std::vector<ex> program = record_program(scene, c, orientation, invariants);
    const std::vector<ex> events = event_programs(scene, c.f);
    if (taylor) c.taylor_call = taylor_call(scene.integrator);
    std::vector<std::string> constants;
    for (const auto& k : lowered.constants)
        constants.push_back(k.name.substr(2)); // p.c000 -> c000
    std::string source = header.text +
                         entry_points(c.f, header.unit, program, events, c.taylor_call, constants,
                                      sensitivity_programs(scene, c.f, program, events)) +
                         (scene.sensitivities.active()
                              ? variational_entry(c.f, sensitivity_key_names(scene, c.f).size())
                              : "");
    if (taylor && scene.sensitivities.active())
        source += augmented_taylor(scene, c.f, header.unit, c.taylor_forcing, timings);
    const std::string flags = taylor ? host_exact_vector_flags() : "";
    c.lib = timings.time("compile", header.unit,
                         [&] { return compile_and_load(source, header.unit, flags); });
    c.header = header.text, c.unit = header.unit;
    c.sys.n = c.f.state.size();
    c.sys.f = reinterpret_cast<loaded_system::kernel>(c.lib.symbol("rotgen_rhs"));
    c.sys.jac = reinterpret_cast<loaded_system::kernel>(c.lib.symbol("rotgen_jacobian"));
    c.prepare = reinterpret_cast<void (*)(const double*, double*)>(c.lib.symbol("rotgen_prepare"));
    c.constants = constants;
    c.record = reinterpret_cast<loaded_system::kernel>(c.lib.symbol("rotgen_record"));
    for (std::size_t e = 0; e < events.size(); ++e)
        c.events.push_back(reinterpret_cast<loaded_system::kernel>(
            c.lib.symbol("rotgen_event_" + std::to_string(e))));
    if (scene.sensitivities.active()) {
        c.record_jacobian =
            reinterpret_cast<loaded_system::kernel>(c.lib.symbol("rotgen_record_jacobian"));
        c.variational = reinterpret_cast<loaded_system::kernel>(c.lib.symbol("rotgen_variational"));
        for (std::size_t e = 0; e < events.size(); ++e)
            c.event_jacobians.push_back(reinterpret_cast<loaded_system::kernel>(
                c.lib.symbol("rotgen_event_jacobian_" + std::to_string(e))));
    }
    if (taylor) {
        c.sys.tay = reinterpret_cast<loaded_system::taylor_kernel>(c.lib.symbol("rotgen_taylor"));
        using count_fn = unsigned long (*)();
        c.sys.series = reinterpret_cast<count_fn>(c.lib.symbol("rotgen_taylor_series"))();
        if (scene.sensitivities.active()) {
            c.taylor_sensitivity = reinterpret_cast<loaded_system::taylor_kernel>(
                c.lib.symbol("rotgen_taylor_sensitivity"));
            c.taylor_sensitivity_series =
                reinterpret_cast<count_fn>(c.lib.symbol("rotgen_taylor_sensitivity_series"))();
        }
    }
    return c;
}

double source_value(const euler_sequence& s, const value_source& src,
                    Eigen::Ref<const Eigen::VectorXd> y, const std::vector<double>& out,
                    const Eigen::Matrix3d& inertia, std::optional<std::array<double, 3>>& e) {
    return source_value_of<double>(s, src, y.data(), out.data(), inertia, e);
}

} // namespace rotgen
