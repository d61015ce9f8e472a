// rotgen — a member's initial kinematics in quad precision (quad_start.hpp).
#include "run/quad_start.hpp"

#include "expr/numbers.hpp"
#include "expr/symbols.hpp"
#include "support/format.hpp"

#include "run/angle_chart.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>

#ifdef ROTGEN_HAVE_QUADMATH
#include "lower/quad.hpp"
extern "C" {
#include <quadmath.h>
}
#endif

namespace rotgen {

bool quad_start::available() {
#ifdef ROTGEN_HAVE_QUADMATH
    return true;
#else
    return false;
#endif
}

#ifndef ROTGEN_HAVE_QUADMATH

struct quad_start::programs {};
quad_start::quad_start(const scene_spec& scene, const derivation& d) : m_scene(scene), m_d(d) {}
quad_start::~quad_start() = default;
const quad_start::programs* quad_start::programs_for(const start_values&) const {
    return nullptr;
}
initial_kinematics quad_start::kinematics(const programs&, const start_values&) const {
    throw std::logic_error("run: built without quad precision");
}

#else

namespace {

using GiNaC::ex;

// The values a program reads: slots of the member (0..2 the angles, 3..5 the initial rates, 6..
// the model parameters) and the rates q_dot computed from momenta or omega.
constexpr int first_rate = 3, first_parameter = 6, computed_rate = -1; // computed: -1 - i

struct slot_source {
    ex symbol;
    std::string name;
    int slot; // a member slot, or computed_rate - i for q_dot_i
};

// The shortest decimal that reads back as x (the exact value of a plain number, as
// exact_scene_value gives it), in long double and in quad; and a quad result in long double.
// Zero is +0 in all three: GiNaC has no -0.
struct exact_decimal {
    long double ld;
    quad q;
};
exact_decimal read_decimal(double x) {
    if (x == 0) return {0.0L, 0};
    const std::string text = format_double(x);
    return {std::strtold(text.c_str(), nullptr), strtoflt128(text.c_str(), nullptr)};
}
// read_decimal(x), remembered: a sweep's members share all but their varied values, and writing
// and reading a decimal back costs about as much as the rest of a member's start in quad
// precision. Each thread keeps the last values it read (bounded).
const exact_decimal& decimal_of(double x) {
    thread_local std::unordered_map<double, exact_decimal> seen;
    if (const auto it = seen.find(x); it != seen.end()) return it->second;
    if (seen.size() >= 256) seen.clear();
    return seen.emplace(x, read_decimal(x)).first->second;
}
long double long_double_of(double x) {
    return decimal_of(x).ld;
}
quad quad_of(double x) {
    return decimal_of(x).q;
}
long double rounded(quad x) {
    return x == 0 ? 0.0L : static_cast<long double>(x);
}

} // namespace

struct quad_start::programs {
    struct one {
        std::optional<quad_program> program;
        std::vector<int> reads; // per input: its slot, or computed_rate - i
    };
    one kinematics; // p (3) and omega (3) at q, q_dot and the parameters
    one mass;       // M(q) = dp/dq_dot, row by row (initial momenta)
    one rates;      // q_dot = J^{-1} omega (initial omega)
    std::vector<char> in_effect;
    std::vector<long double> slot_value; // the expression slots' values in long double
};

quad_start::quad_start(const scene_spec& scene, const derivation& d) : m_scene(scene), m_d(d) {}
quad_start::~quad_start() = default;

namespace {

const written_value* written_of(const scene_spec& scene, std::size_t slot) {
    if (slot < first_rate) return &scene.angles_written[slot];
    if (slot < first_parameter) return &scene.rates_written[slot - first_rate];
    const std::size_t j = slot - first_parameter;
    return j < scene.parameters_written.size() ? &scene.parameters_written[j] : nullptr;
}

double current_of(const start_values& v, std::size_t slot) {
    if (slot < first_rate) return v.angles[slot];
    if (slot < first_parameter) return v.rates[slot - first_rate];
    return v.parameters[slot - first_parameter];
}

// `outputs` lowered over `sources`, the slots in effect as expressions substituted exactly.
quad_start::programs::one lowered(std::vector<ex> outputs, const std::vector<slot_source>& sources,
                                  const std::vector<char>& in_effect,
                                  const std::vector<written_value>& written) {
    GiNaC::exmap exact;
    quad_start::programs::one p;
    std::vector<program_input> inputs;
    for (const slot_source& s : sources) {
        if (s.slot >= 0 && in_effect[static_cast<std::size_t>(s.slot)]) {
            exact[s.symbol] = written[static_cast<std::size_t>(s.slot)].exact;
            continue;
        }
        inputs.push_back({s.symbol, s.name, "", s.slot >= first_parameter});
        p.reads.push_back(s.slot);
    }
    for (ex& e : outputs)
        e = e.subs(exact, GiNaC::subs_options::no_pattern);
    p.program.emplace(lower(outputs, inputs));
    return p;
}

// The programs for one set of slots in effect as expressions.
std::unique_ptr<quad_start::programs> build(const scene_spec& scene, const derivation& d,
                                            const std::vector<char>& in_effect,
                                            const std::vector<written_value>& written) {
    const auto& s = symbols();
    const auto& names = scene.model.angles.names;
    std::vector<slot_source> angles, parameters;
    for (int i = 0; i < 3; ++i)
        angles.push_back({s.q[i], names[i], i});
    for (std::size_t j = 0; j < scene.model.parameters.size(); ++j)
        parameters.push_back({scene.model.parameters[j].symbol, scene.model.parameters[j].name,
                              first_parameter + static_cast<int>(j)});
    const auto with = [](std::vector<slot_source> a, const std::vector<slot_source>& b) {
        a.insert(a.end(), b.begin(), b.end());
        return a;
    };
    auto p = std::make_unique<quad_start::programs>();
    std::vector<slot_source> rates;
    for (int i = 0; i < 3; ++i)
        rates.push_back(
            {s.qd[i], names[i] + "_dot",
             scene.initial == initial_kind::rates ? first_rate + i : computed_rate - i});
    std::vector<ex> out(d.momenta.begin(), d.momenta.end());
    if (d.wheels.driven) // a wheel's rate drive: p depends on t
        for (ex& e : out)
            e = e.subs(s.t == GiNaC::numeric(scene.t_start));
    out.insert(out.end(), d.omega.begin(), d.omega.end());
    p->kinematics = lowered(out, with(with(angles, rates), parameters), in_effect, written);
    if (scene.initial == initial_kind::momenta) {
        out.clear();
        for (const auto& row : d.mass_matrix)
            out.insert(out.end(), row.begin(), row.end());
        p->mass = lowered(out, with(angles, parameters), in_effect, written);
    }
    if (scene.initial == initial_kind::omega) {
        std::vector<slot_source> omega;
        out.assign(3, 0);
        for (int j = 0; j < 3; ++j) {
            omega.push_back({s.omega[j], "omega" + std::to_string(j + 1), first_rate + j});
            for (int i = 0; i < 3; ++i)
                out[i] += d.inverse_omega_jacobian[i][j] * s.omega[j];
        }
        p->rates = lowered(out, with(with(angles, omega), parameters), in_effect, written);
    }
    p->in_effect = in_effect;
    p->slot_value.assign(in_effect.size(), 0);
    const scoped_digits digits(30);
    for (std::size_t k = 0; k < in_effect.size(); ++k)
        if (in_effect[k]) p->slot_value[k] = to_long_double(written[k].exact);
    return p;
}

} // namespace

const quad_start::programs* quad_start::programs_for(const start_values& v) const {
    const std::size_t slots = first_parameter + v.parameters.size();
    std::vector<char> in_effect(slots, 0);
    std::vector<written_value> written(slots);
    for (std::size_t s = 0; s < slots; ++s)
        if (const written_value* w = written_of(m_scene, s)) {
            in_effect[s] = w->expression && w->value == current_of(v, s);
            written[s] = *w;
        }
    auto it = m_programs.find(in_effect);
    if (it != m_programs.end()) return it->second.get();
    std::unique_ptr<programs> p;
    try {
        p = build(m_scene, m_d, in_effect, written);
    } catch (const std::logic_error&) { // a call without a quad function: GiNaC it is
    }
    return m_programs.emplace(in_effect, std::move(p)).first->second.get();
}

namespace {

// A program's outputs at `v`, with `qd` for the rates it computes.
std::vector<quad> run(const quad_start::programs::one& p, const start_values& v,
                      const std::array<quad, 3>& qd = {}) {
    std::vector<quad> in;
    in.reserve(p.reads.size());
    for (int r : p.reads)
        in.push_back(r >= 0 ? quad_of(current_of(v, static_cast<std::size_t>(r)))
                            : qd[static_cast<std::size_t>(computed_rate - r)]);
    return p.program->evaluate(in);
}

} // namespace

initial_kinematics quad_start::kinematics(const programs& p, const start_values& v) const {
    const auto value = [&](std::size_t slot) {
        return p.in_effect[slot] ? p.slot_value[slot] : long_double_of(current_of(v, slot));
    };
    initial_kinematics k;
    for (std::size_t i = 0; i < 3; ++i)
        k.q[i] = value(i);
    const euler_sequence sequence = sequence_of(m_scene.model.angles);
    k.have_rates =
        m_scene.initial == initial_kind::rates || chart_distance(sequence, v.angles[1]) >= 1e-12;
    std::array<quad, 3> qd{};
    if (m_scene.initial == initial_kind::rates) {
        for (std::size_t i = 0; i < 3; ++i) {
            k.qd[i] = value(first_rate + i);
            qd[i] = quad_of(v.rates[i]); // read unless substituted
        }
    } else if (k.have_rates && m_scene.initial == initial_kind::momenta) {
        // q_dot = M(q)^{-1} p in long double, as initial_kinematics_of() solves it
        const std::vector<quad> m = run(p.mass, v);
        Eigen::Matrix<long double, 3, 3> M;
        Eigen::Matrix<long double, 3, 1> momenta;
        for (int i = 0; i < 3; ++i) {
            momenta[i] = value(first_rate + static_cast<std::size_t>(i));
            for (int j = 0; j < 3; ++j)
                M(i, j) = rounded(m[static_cast<std::size_t>(3 * i + j)]);
        }
        const std::array<std::string, 3> text = rates_text(M, momenta);
        for (std::size_t i = 0; i < 3; ++i) {
            qd[i] = strtoflt128(text[i].c_str(), nullptr);
            k.qd[i] = std::strtold(text[i].c_str(), nullptr);
        }
    } else if (k.have_rates) {
        const std::vector<quad> r = run(p.rates, v);
        for (std::size_t i = 0; i < 3; ++i) {
            qd[i] = r[i];
            k.qd[i] = rounded(r[i]);
        }
    }
    if (k.have_rates) {
        const std::vector<quad> out = run(p.kinematics, v, qd);
        for (std::size_t i = 0; i < 3; ++i) {
            k.p[i] = rounded(out[i]);
            k.omega[i] = rounded(out[3 + i]);
        }
    }
    if (m_scene.initial == initial_kind::omega)
        for (std::size_t i = 0; i < 3; ++i)
            k.omega[i] = value(first_rate + i);
    k.quat = quaternion_of_angles<long double>(sequence, k.q[0], k.q[1], k.q[2]);
    return k;
}

} // namespace rotgen

#endif
