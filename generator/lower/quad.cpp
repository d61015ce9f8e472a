// rotgen — a lowered program evaluated in quad precision (quad.hpp).
#ifdef ROTGEN_HAVE_QUADMATH

#include "lower/quad.hpp"

#include "expr/numbers.hpp"

extern "C" {
#include <quadmath.h>
}

#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rotgen {

namespace {

quad from_text(const GiNaC::numeric& n) {
    std::ostringstream os;
    os << n;
    return strtoflt128(os.str().c_str(), nullptr);
}

quad absolute(quad x) {
    return fabsq(x);
}

quad pi() { // M_PIq, without the Q literal suffix that needs GNU extensions
    return strtoflt128("3.14159265358979323846264338327950288419716939937510582097494", nullptr);
}

struct call_entry {
    quad (*f1)(quad) = nullptr;
    quad (*f2)(quad, quad) = nullptr;
};

const std::map<std::string, call_entry>& calls() {
    static const std::map<std::string, call_entry> c{
        {"sin", {sinq}},         {"cos", {cosq}},
        {"tan", {tanq}},         {"asin", {asinq}},
        {"acos", {acosq}},       {"atan", {atanq}},
        {"sinh", {sinhq}},       {"cosh", {coshq}},
        {"tanh", {tanhq}},       {"exp", {expq}},
        {"log", {logq}},         {"abs", {absolute}},
        {"sqrt", {sqrtq}},       {"atan2", {nullptr, atan2q}},
        {"pow", {nullptr, powq}}};
    return c;
}

} // namespace

quad to_quad(const GiNaC::numeric& n) {
    const GiNaC::numeric num = n.numer(), den = n.denom();
    if (num.int_length() <= 113 && den.int_length() <= 113)
        return from_text(num) / from_text(den); // both exact: one rounding
    const scoped_digits digits(40);
    return from_text(GiNaC::ex_to<GiNaC::numeric>(n.evalf()));
}

quad_program::quad_program(const lowered_program& program)
    : m_inputs(program.inputs.size()), m_nodes(program.nodes.size()), m_outputs(program.outputs) {
    std::vector<char> reached(program.nodes.size(), 0);
    std::vector<int> stack(program.outputs.begin(), program.outputs.end());
    while (!stack.empty()) {
        const auto id = static_cast<std::size_t>(stack.back());
        stack.pop_back();
        if (reached[id]) continue;
        reached[id] = 1;
        for (int c : node_children(program.nodes[id]))
            stack.push_back(c);
    }
    std::map<std::string, int> input_at;
    for (std::size_t i = 0; i < program.inputs.size(); ++i)
        input_at[program.inputs[i].name] = static_cast<int>(i);
    for (std::size_t i = 0; i < program.nodes.size(); ++i) {
        if (!reached[i]) continue;
        const lowered_node& n = program.nodes[i];
        instruction in;
        in.k = n.k;
        if (n.k == lowered_node::kind::input) in.input = input_at.at(n.name);
        if (n.k == lowered_node::kind::number || n.k == lowered_node::kind::sum)
            in.value = to_quad(n.value);
        if (n.k == lowered_node::kind::constant) in.value = pi();
        for (const auto& [c, id] : n.terms)
            in.terms.emplace_back(to_quad(c), id);
        in.numerator = n.numerator;
        in.denominator = n.denominator;
        in.args = n.args;
        if (n.k == lowered_node::kind::call) {
            const auto it = calls().find(n.name);
            if (it == calls().end())
                throw std::logic_error("lower: no quad function for " + n.name);
            in.f1 = it->second.f1;
            in.f2 = it->second.f2;
        }
        m_code.emplace_back(static_cast<int>(i), std::move(in));
    }
}

quad quad_program::run(const instruction& in, const std::vector<quad>& v,
                       const std::vector<quad>& inputs) const {
    const auto at = [&](int id) { return v[static_cast<std::size_t>(id)]; };
    quad r = in.value;
    switch (in.k) {
    case lowered_node::kind::input:
        return inputs[static_cast<std::size_t>(in.input)];
    case lowered_node::kind::number:
    case lowered_node::kind::constant:
        return r;
    case lowered_node::kind::sum:
        for (const auto& [c, id] : in.terms)
            r += c == 1 ? at(id) : c == -1 ? -at(id) : c * at(id);
        return r;
    case lowered_node::kind::product:
        r = 1;
        for (int id : in.numerator)
            r *= at(id);
        for (int id : in.denominator)
            r /= at(id);
        return r;
    case lowered_node::kind::call:
        return in.f1 ? in.f1(at(in.args.at(0))) : in.f2(at(in.args.at(0)), at(in.args.at(1)));
    }
    throw std::logic_error("lower: unknown node kind");
}

std::vector<quad> quad_program::evaluate(const std::vector<quad>& inputs) const {
    if (inputs.size() != m_inputs) throw std::logic_error("quad_program: wrong number of inputs");
    std::vector<quad> v(m_nodes);
    for (const auto& [id, in] : m_code)
        v[static_cast<std::size_t>(id)] = run(in, v, inputs);
    std::vector<quad> out;
    out.reserve(m_outputs.size());
    for (int o : m_outputs)
        out.push_back(v[static_cast<std::size_t>(o)]);
    return out;
}

} // namespace rotgen

#endif
