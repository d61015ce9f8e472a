// rotgen — lowering of a whole form (lower_form.hpp): outputs, specialisation, candidate choice
// and the Jacobian's structural zeros.
#include "lower/lower_form.hpp"

#include "expr/print.hpp"
#include "support/error.hpp"

#include <algorithm>
#include <cstdio>
#include <random>
#include <regex>
#include <stdexcept>

namespace rotgen {

using GiNaC::ex;
using GiNaC::numeric;

numeric exact_decimal(double x) {
    // format_double gives the shortest text that reads back as x: "9.81", "1e-12", "-0.3", "2.0".
    const std::string s = format_double(x);
    static const std::regex decimal("([+-]?)([0-9]*)\\.?([0-9]*)(?:[eE]([+-]?[0-9]+))?");
    std::smatch m;
    if (!std::regex_match(s, m, decimal))
        throw std::logic_error("exact_decimal: cannot read back '" + s + "'");
    std::string digits = m[2].str() + m[3].str();
    digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size()));
    long exponent = m[4].matched ? std::stol(m[4].str()) : 0;
    exponent -= static_cast<long>(m[3].length());
    numeric v(digits.empty() ? std::string("0").c_str() : digits.c_str());
    v *= numeric(10).power(numeric(exponent));
    return m[1].str() == "-" ? -v : v;
}

namespace {

const std::string where = "rotgen emit";

std::string join(const std::vector<std::string>& v, const std::string& sep) {
    std::string s;
    for (std::size_t i = 0; i < v.size(); ++i)
        s += (i ? sep : "") + v[i];
    return s;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

void check_output_names(const std::vector<std::string>& requested) {
    const auto& all = output_names();
    for (const auto& r : requested)
        if (!contains(all, r)) {
            const std::string best = closest_name(r, all);
            throw user_error({where}, "unknown output '" + r + "' (expected some of " +
                                          join(all, ", ") + ")" +
                                          (best.empty() ? "" : "; did you mean '" + best + "'?"));
        }
}

// Whether an output mentions t (a wheel's rate drive, derive/wheels.hpp): the header's output
// functions take no t.
bool depends_on_time(const form_expressions& f, const std::string& name) {
    const auto it = f.outputs.find(name);
    if (it == f.outputs.end()) return false;
    for (const GiNaC::ex& e : it->second.values)
        if (e.has(f.time)) return true;
    return false;
}

// The outputs to write, in output_names()' order, whatever order the request gave.
std::vector<std::string> resolve_outputs(const model_spec& spec, const form_expressions& f,
                                         const std::vector<std::string>& asked) {
    const auto& all = output_names();
    check_output_names(asked);
    std::vector<std::string> requested = asked;
    if (requested.empty()) {
        requested = {"rhs", "jacobian"};
        for (const auto& name : all)
            if (f.outputs.count(name) && !depends_on_time(f, name)) requested.push_back(name);
    }
    for (const auto& r : requested)
        if (depends_on_time(f, r))
            throw user_error({where}, std::string("the ") + to_string(f.form) + " form of '" +
                                          spec.name + "' cannot give '" + r +
                                          "' in a header: it depends on t (a wheel's rate "
                                          "drive), and the output functions take no t; "
                                          "`rotgen simulate` records it");
    for (const auto& r : requested)
        if (r != "rhs" && r != "jacobian" && r != "taylor" && !f.outputs.count(r)) {
            const auto why = f.unavailable.find(r);
            throw user_error(
                {where}, std::string("the ") + to_string(f.form) + " form of '" + spec.name +
                             "' cannot give '" + r +
                             "': " + (why != f.unavailable.end() ? why->second : "not available"));
        }
    std::vector<std::string> outputs;
    for (const auto& name : all)
        if (contains(requested, name)) outputs.push_back(name);
    return outputs;
}

// Specialisation: which parameters are folded into the code (never the reduced form's conserved
// momenta), as symbol -> exact value.
struct folding {
    GiNaC::exmap values;
    std::vector<std::string> text; // "I1 = 1.5"
    std::vector<form_parameter> runtime;
};

folding choose_folding(const model_spec& spec, const form_expressions& f,
                       const kernel_request& request) {
    std::vector<std::string> names;
    for (const auto& p : f.parameters)
        if (p.specialisable) names.push_back(p.name);
    for (const auto& s : request.specialise)
        if (!contains(names, s)) {
            const std::string best = closest_name(s, names);
            throw user_error({where}, "--specialise: model '" + spec.name + "' has no parameter '" +
                                          s + "'" +
                                          (best.empty() ? "" : "; did you mean '" + best + "'?"));
        }
    folding r;
    for (const auto& p : f.parameters) {
        if (p.specialisable && (request.specialise_all || contains(request.specialise, p.name))) {
            r.values[p.symbol] = exact_decimal(p.value);
            r.text.push_back(p.name + " = " + format_double(p.value));
        } else {
            r.runtime.push_back(p);
        }
    }
    return r;
}

// The form with the folded values substituted into every expression.
form_expressions substituted(form_expressions f, const GiNaC::exmap& folded) {
    if (folded.empty()) return f;
    const auto subs = [&](std::vector<ex>& v) {
        for (auto& e : v)
            e = e.subs(folded);
    };
    subs(f.rates);
    for (auto& alt : f.alternative_rates)
        subs(alt);
    for (auto& row : f.mass)
        for (auto& e : row)
            e = e.subs(folded);
    for (auto& e : f.forcing)
        e = e.subs(folded);
    for (auto& [name, out] : f.outputs) {
        subs(out.values);
        for (auto& alt : out.alternatives)
            subs(alt);
    }
    return f;
}

// Which entries of a (row-major, n columns) matrix of expressions vanish identically: evaluated
// with 40 significant digits at 4 fixed pseudo-random points (every input drawn, parameters too),
// an entry below 1e-28 of its row's largest is taken for zero. A non-zero analytic expression is
// that small at four random points with probability nil; the points are fixed, so the answer is
// the same in every run.
std::vector<bool> identically_zero(const std::vector<ex>& entries,
                                   const std::vector<program_input>& inputs, std::size_t n) {
    const lowered_program prog = lower(entries, inputs);
    std::vector<bool> zero(entries.size(), true);
    std::vector<numeric> scale(entries.size() / n, numeric(0));
    std::vector<std::vector<numeric>> values;
    const long saved = GiNaC::Digits;
    GiNaC::Digits = 40;
    std::mt19937 rng(20240607);
    std::uniform_int_distribution<int> draw(300, 2800); // thousandths: angles in (0.3, 2.8)
    try {
        for (int point = 0; point < 4; ++point) {
            GiNaC::exmap at;
            for (const auto& in : inputs)
                at[in.symbol] = numeric(draw(rng), 1000);
            values.push_back(evaluate(prog, at));
        }
    } catch (...) {
        GiNaC::Digits = saved;
        throw;
    }
    GiNaC::Digits = saved;
    for (const auto& v : values)
        for (std::size_t i = 0; i < entries.size(); ++i) {
            const numeric a = abs(v[i]);
            if (a > scale[i / n]) scale[i / n] = a;
        }
    for (const auto& v : values)
        for (std::size_t i = 0; i < entries.size(); ++i)
            if (abs(v[i]) > numeric(1, 10).power(28) * std::max(scale[i / n], numeric(1)))
                zero[i] = false;
    return zero;
}

using candidates = std::vector<std::vector<ex>>;

candidates candidates_of(const form_output& out) {
    candidates c{out.values};
    c.insert(c.end(), out.alternatives.begin(), out.alternatives.end());
    return c;
}

candidates rate_candidates_of(const form_expressions& f) {
    candidates c{f.rates};
    c.insert(c.end(), f.alternative_rates.begin(), f.alternative_rates.end());
    return c;
}

// Lowers and chooses among candidates: the substituted ones (`candidates`, lowered with `inputs`)
// and, with specialisation, the runtime ones (`runtime`, lowered with `runtime_inputs`, the folded
// parameters among them, then folded). The substituted candidates come first and win ties.
class chooser {
  public:
    chooser(std::vector<program_input> inputs, std::vector<program_input> runtime_inputs,
            GiNaC::exmap folded)
        : m_inputs(std::move(inputs)), m_runtime_inputs(std::move(runtime_inputs)),
          m_folded(std::move(folded)) {}

    const std::vector<program_input>& inputs() const { return m_inputs; }
    bool folding() const { return !m_folded.empty(); }

    // hoist: lower_options::hoist_parameters
    lowered_program best(const candidates& substituted, const candidates& runtime,
                         bool hoist = false) const {
        lower_options options;
        options.hoist_parameters = hoist;
        const auto cost = [](const op_count& o) { return o.add + o.mul + 4 * o.div + 20 * o.call; };
        const auto better = [&](const op_count& a, const op_count& b) {
            return cost(a) < cost(b) || (cost(a) == cost(b) && a.total() < b.total());
        };
        std::size_t best = 0;
        std::vector<lowered_program> programs;
        for (const auto& c : substituted) {
            programs.push_back(lower(c, m_inputs, options));
            if (better(programs.back().after, programs[best].after)) best = programs.size() - 1;
        }
        if (folding())
            for (const auto& c : runtime) {
                std::optional<lowered_program> p =
                    lower_folded(c, m_runtime_inputs, m_folded, options);
                if (!p) continue;
                programs.push_back(std::move(*p));
                if (better(programs.back().after, programs[best].after)) best = programs.size() - 1;
            }
        return std::move(programs[best]);
    }

  private:
    std::vector<program_input> m_inputs, m_runtime_inputs;
    GiNaC::exmap m_folded;
};

chooser make_chooser(const form_expressions& f, const folding& fold) {
    std::vector<program_input> inputs;
    for (std::size_t i = 0; i < f.state.size(); ++i)
        inputs.push_back({f.state[i].symbol, f.state[i].name, "y[" + std::to_string(i) + "]"});
    // Model constants are parameters of the lowering (their coefficients become single
    // fractions); the reduced form's conserved momenta are initial data, like the state.
    for (const auto& p : fold.runtime)
        inputs.push_back({p.symbol, "p." + p.name, "", p.specialisable});
    std::vector<program_input> runtime_inputs = inputs;
    for (const auto& p : f.parameters)
        if (fold.values.count(p.symbol))
            runtime_inputs.push_back({p.symbol, "p." + p.name, "", true});
    inputs.push_back({f.time, "t", ""});
    runtime_inputs.push_back({f.time, "t", ""});
    return chooser(std::move(inputs), std::move(runtime_inputs), fold.values);
}

std::vector<std::string> indexed(const std::string& array, std::size_t count) {
    std::vector<std::string> v;
    for (std::size_t i = 0; i < count; ++i)
        v.push_back(array + "[" + std::to_string(i) + "]");
    return v;
}

// The Jacobian's candidates (one per rate candidate), its structural zeros set to 0 in each, and
// the same for the runtime candidates; `zero` receives the pattern.
struct jacobian_candidates {
    candidates jac, both, runtime_jac, runtime_both;
};

jacobian_candidates jacobians(const form_expressions& f, const form_expressions& runtime_f,
                              const chooser& choose, std::vector<bool>& zero) {
    const std::size_t n = f.state.size();
    const candidates rates = rate_candidates_of(f);
    jacobian_candidates r;
    // An entry that is exactly 0 by any route is 0, and so is an entry that vanishes
    // identically (an identity such as sin^2 + cos^2 = 1 cancels it).
    zero.assign(n * n, false);
    for (const auto& rate : rates)
        r.jac.push_back(jacobian(f, rate));
    for (const auto& J : r.jac)
        for (std::size_t i = 0; i < n * n; ++i)
            zero[i] = zero[i] || J[i].is_zero();
    const std::vector<bool> vanishing = identically_zero(r.jac[0], choose.inputs(), n);
    for (std::size_t i = 0; i < n * n; ++i)
        zero[i] = zero[i] || vanishing[i];
    const auto both = [&](std::vector<ex> rate, std::vector<ex>& J) {
        for (std::size_t i = 0; i < n * n; ++i)
            if (zero[i]) J[i] = 0;
        rate.insert(rate.end(), J.begin(), J.end());
        return rate;
    };
    for (std::size_t c = 0; c < rates.size(); ++c)
        r.both.push_back(both(rates[c], r.jac[c]));
    // Entries zero for the folded values are zero in the runtime versions too.
    if (choose.folding())
        for (const auto& rate : rate_candidates_of(runtime_f)) {
            std::vector<ex> J = jacobian(runtime_f, rate);
            r.runtime_both.push_back(both(rate, J));
            r.runtime_jac.push_back(std::move(J));
        }
    return r;
}

// The sensitivity keys (kernel_request::sensitivities): parameters.<name> of a model parameter
// that is not folded, each once, and not with the taylor output; their parameters, in order.
std::vector<form_parameter> sensitivity_parameters(const model_spec& spec,
                                                   const form_expressions& f,
                                                   const kernel_request& request,
                                                   const folding& fold,
                                                   const std::vector<std::string>& outputs) {
    const std::string option = "--sensitivities: ", prefix = "parameters.";
    if (!request.sensitivities.empty() && contains(outputs, "taylor"))
        throw user_error({where}, option + "no Taylor recurrences for the variational equations "
                                           "yet; leave taylor out of --outputs");
    std::vector<std::string> names, seen;
    for (const auto& p : f.parameters)
        if (p.specialisable) names.push_back(p.name);
    std::vector<form_parameter> r;
    for (const auto& key : request.sensitivities) {
        if (contains(seen, key)) throw user_error({where}, option + "'" + key + "' given twice");
        seen.push_back(key);
        if (key.compare(0, prefix.size(), prefix) != 0)
            throw user_error({where}, option + "'" + key +
                                          "' is not a parameter key (emit takes "
                                          "parameters.<name>)");
        const std::string name = key.substr(prefix.size());
        const auto it = std::find_if(f.parameters.begin(), f.parameters.end(), [&](const auto& p) {
            return p.specialisable && p.name == name;
        });
        if (it == f.parameters.end()) {
            const std::string best = closest_name(name, names);
            throw user_error({where},
                             option + "'" + key + "': model '" + spec.name +
                                 "' has no parameter '" + name + "'" +
                                 (best.empty() ? "" : "; did you mean '" + prefix + best + "'?"));
        }
        if (fold.values.count(it->symbol))
            throw user_error({where}, option + "'" + key +
                                          "' is folded into the code by --specialise; leave " +
                                          name + " out of --specialise");
        r.push_back(*it);
    }
    return r;
}

// Where every candidate's (row-major, `columns` wide) entries are structurally zero: exactly 0 by
// any route, or vanishing identically.
std::vector<bool> zero_pattern(const candidates& c, const std::vector<program_input>& inputs,
                               std::size_t columns) {
    std::vector<bool> zero(c[0].size(), false);
    for (const auto& entries : c)
        for (std::size_t i = 0; i < entries.size(); ++i)
            zero[i] = zero[i] || entries[i].is_zero();
    const std::vector<bool> vanishing = identically_zero(c[0], inputs, columns);
    for (std::size_t i = 0; i < zero.size(); ++i)
        zero[i] = zero[i] || vanishing[i];
    return zero;
}

// The rates of each rate candidate of a form, with their d f/d y and d f/d p.
struct derivative_candidates {
    candidates rates, J, P;
};

derivative_candidates derivatives_of(const form_expressions& f, const std::vector<ex>& symbols) {
    derivative_candidates d;
    d.rates = rate_candidates_of(f);
    for (const auto& rate : d.rates) {
        d.J.push_back(jacobian(f, rate));
        d.P.push_back(parameter_jacobian(f, rate, symbols));
    }
    return d;
}

// The candidates of parameter_jacobian (d f/d p, its zeros 0) and of variational_rhs (f, then the
// entries of d f/d y neither zero nor 1 and the non-zero ones of d f/d p), one per rate candidate.
struct sensitivity_candidates {
    candidates dfdp, variational;
};

sensitivity_candidates sensitivity_candidates_of(const derivative_candidates& d,
                                                 const lowered_form& r) {
    sensitivity_candidates c;
    for (std::size_t j = 0; j < d.rates.size(); ++j) {
        std::vector<ex> P = d.P[j], all = d.rates[j];
        for (std::size_t i = 0; i < d.J[j].size(); ++i)
            if (!r.sensitivity_dfdy_zero[i] && !r.sensitivity_dfdy_one[i]) all.push_back(d.J[j][i]);
        for (std::size_t i = 0; i < P.size(); ++i)
            if (r.sensitivity_dfdp_zero[i])
                P[i] = 0;
            else
                all.push_back(P[i]);
        c.dfdp.push_back(std::move(P));
        c.variational.push_back(std::move(all));
    }
    return c;
}

// parameter_jacobian and variational_rhs (lowered_form::sensitivity_names), with f, d f/d y and
// d f/d p lowered together in variational_rhs: their common subexpressions computed once.
void add_sensitivity_functions(lowered_form& r, const form_expressions& f,
                               const form_expressions& runtime_f, const chooser& choose,
                               const std::vector<form_parameter>& keys) {
    if (keys.empty()) return;
    const std::size_t n = f.state.size(), k = keys.size();
    std::vector<ex> symbols;
    for (const auto& p : keys) {
        symbols.push_back(p.symbol);
        r.sensitivity_names.push_back(p.name);
    }
    const derivative_candidates d = derivatives_of(f, symbols);
    r.sensitivity_dfdy_zero = zero_pattern(d.J, choose.inputs(), n);
    r.sensitivity_dfdp_zero = zero_pattern(d.P, choose.inputs(), k);
    r.sensitivity_dfdy_one.assign(n * n, true); // q_dot = q_dot: the product needs no factor
    for (const auto& entries : d.J)
        for (std::size_t i = 0; i < n * n; ++i)
            r.sensitivity_dfdy_one[i] = r.sensitivity_dfdy_one[i] && entries[i].is_equal(1);
    const sensitivity_candidates c = sensitivity_candidates_of(d, r);
    const sensitivity_candidates runtime =
        choose.folding() ? sensitivity_candidates_of(derivatives_of(runtime_f, symbols), r)
                         : sensitivity_candidates{};
    std::vector<std::string> targets = indexed("dydt", n);
    const auto local = [](const std::string& name, std::size_t i, std::size_t j) {
        return "const T " + name + "_" + std::to_string(i) + "_" + std::to_string(j);
    };
    for (std::size_t i = 0; i < n * n; ++i)
        if (!r.sensitivity_dfdy_zero[i] && !r.sensitivity_dfdy_one[i])
            targets.push_back(local("dfdy", i / n, i % n));
    for (std::size_t i = 0; i < n * k; ++i)
        if (!r.sensitivity_dfdp_zero[i]) targets.push_back(local("dfdp", i / k, i % k));
    r.functions.push_back({"parameter_jacobian",
                           choose.best(c.dfdp, runtime.dfdp, true),
                           indexed("dfdp", n * k),
                           std::vector<std::string>{"t", "y", "p"},
                           {}});
    r.functions.push_back({"variational_rhs", choose.best(c.variational, runtime.variational, true),
                           targets, std::vector<std::string>{"t", "y", "S", "p"}, f.rate_names});
}

// The hoisted constants of all the functions, named once for the form: equal ones (the same
// digest: the same expression) share a name, p.c000, p.c001, ... in order of first appearance
// (children before parents, as each program lists them).
void name_constants(lowered_form& r) {
    std::map<std::uint64_t, std::string> names;
    for (std::size_t f = 0; f < r.functions.size(); ++f) {
        lowered_program& p = r.functions[f].program;
        for (auto& c : p.constants) {
            char name[32];
            std::snprintf(name, sizeof name, "p.c%03zu", names.size());
            const auto [it, fresh] =
                names.emplace(p.nodes[static_cast<std::size_t>(c.node)].digest, name);
            c.name = it->second;
            p.temporary_name[c.node] = c.name;
            if (fresh) r.constants.push_back({f, c.node, c.name});
        }
    }
}

} // namespace

form_expressions build_requested_form(const model_spec& spec, const derivation& d, form_kind form,
                                      lagrangian_strategy strategy, const kernel_request& request) {
    check_output_names(request.outputs);
    return build_form(spec, d, form, strategy, contains(request.outputs, "rotation"));
}

lowered_form lower_form(const model_spec& spec, const form_expressions& runtime_f,
                        const kernel_request& request) {
    const std::vector<std::string> outputs = resolve_outputs(spec, runtime_f, request.outputs);
    const folding fold = choose_folding(spec, runtime_f, request);
    const std::vector<form_parameter> keys =
        sensitivity_parameters(spec, runtime_f, request, fold, outputs);
    // The form before substitution (runtime_f): its candidates are lowered with the parameters
    // as inputs and folded afterwards, and compete with the substituted ones.
    const form_expressions f = substituted(runtime_f, fold.values);
    const chooser choose = make_chooser(f, fold);

    lowered_form r;
    r.form = f.form;
    r.strategy = f.strategy;
    for (const auto& s : f.state)
        r.state_names.push_back(s.name);
    r.rate_names = f.rate_names;
    r.notes = f.notes;
    r.runtime_parameters = fold.runtime;
    r.folded = fold.text;

    const std::size_t n = f.state.size();
    const std::vector<std::string> dydt = indexed("dydt", n), J = indexed("J", n * n);
    const auto runtime_rates = choose.folding() ? rate_candidates_of(runtime_f) : candidates{};
    jacobian_candidates jac;
    if (contains(outputs, "jacobian")) jac = jacobians(f, runtime_f, choose, r.jacobian_zero);
    const std::vector<std::string> tyt{"t", "y", "p"};
    for (const auto& name : outputs) {
        if (name == "rhs" || name == "taylor") {
            // taylor: the coefficients of the rhs's own program (emit/taylor.hpp)
            r.functions.push_back({name,
                                   choose.best(rate_candidates_of(f), runtime_rates, name == "rhs"),
                                   dydt, tyt, f.rate_names});
        } else if (name == "jacobian") {
            r.functions.push_back({name, choose.best(jac.jac, jac.runtime_jac, true), J, tyt, {}});
            if (contains(outputs, "rhs")) {
                std::vector<std::string> targets = dydt;
                targets.insert(targets.end(), J.begin(), J.end());
                r.functions.push_back({"rhs_and_jacobian",
                                       choose.best(jac.both, jac.runtime_both, true), targets, tyt,
                                       f.rate_names});
            }
        } else {
            const form_output& out = f.outputs.at(name);
            const candidates runtime =
                choose.folding() ? candidates_of(runtime_f.outputs.at(name)) : candidates{};
            static const std::map<std::string, std::string> array{{"momenta", "momentum"},
                                                                  {"mass_matrix", "M"},
                                                                  {"omega", "w"},
                                                                  {"rotation", "A"},
                                                                  {"ignored_rates", "rates"}};
            const std::vector<std::string> targets =
                name == "energy" ? std::vector<std::string>{"return"}
                                 : indexed(array.at(name), out.values.size());
            r.functions.push_back(
                {name, choose.best(candidates_of(out), runtime), targets, {"y", "p"}, out.names});
        }
    }
    add_sensitivity_functions(r, f, runtime_f, choose, keys);
    name_constants(r);
    return r;
}

} // namespace rotgen
