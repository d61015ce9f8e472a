// rotgen — lowering: a program's value at a point (to check lowering against the original
// expressions), and which inputs it uses.
#include "lower/detail.hpp"

#include <stdexcept>

namespace rotgen {

using GiNaC::ex_to;
using GiNaC::is_a;
using namespace lowering;

// A call as lowering names it (sqrt and pow included), applied to GiNaC arguments.
ex lowering::apply_call(const std::string& name, const std::vector<ex>& a) {
    if (name == "sin") return GiNaC::sin(a.at(0));
    if (name == "cos") return GiNaC::cos(a.at(0));
    if (name == "tan") return GiNaC::tan(a.at(0));
    if (name == "asin") return GiNaC::asin(a.at(0));
    if (name == "acos") return GiNaC::acos(a.at(0));
    if (name == "atan") return GiNaC::atan(a.at(0));
    if (name == "atan2") return GiNaC::atan2(a.at(0), a.at(1));
    if (name == "sinh") return GiNaC::sinh(a.at(0));
    if (name == "cosh") return GiNaC::cosh(a.at(0));
    if (name == "tanh") return GiNaC::tanh(a.at(0));
    if (name == "exp") return GiNaC::exp(a.at(0));
    if (name == "log") return GiNaC::log(a.at(0));
    if (name == "abs") return GiNaC::abs(a.at(0));
    if (name == "sqrt") return GiNaC::sqrt(a.at(0));
    if (name == "pow") return GiNaC::pow(a.at(0), a.at(1));
    throw std::logic_error("lower: cannot evaluate " + name);
}

std::vector<bool> used_inputs(const lowered_program& program) {
    std::vector<char> reached(program.nodes.size(), 0);
    std::vector<int> stack(program.outputs.begin(), program.outputs.end());
    while (!stack.empty()) {
        const int id = stack.back();
        stack.pop_back();
        if (reached[static_cast<std::size_t>(id)]) continue;
        reached[static_cast<std::size_t>(id)] = 1;
        for (int c : children(program.nodes[static_cast<std::size_t>(id)]))
            stack.push_back(c);
    }
    std::vector<bool> used(program.inputs.size(), false);
    for (std::size_t i = 0; i < program.nodes.size(); ++i) {
        const lowered_node& n = program.nodes[i];
        if (!reached[i] || n.k != lowered_node::kind::input) continue;
        for (std::size_t k = 0; k < program.inputs.size(); ++k)
            if (program.inputs[k].name == n.name) used[k] = true;
    }
    return used;
}

std::vector<numeric> evaluate(const lowered_program& program, const GiNaC::exmap& values) {
    std::vector<ex> v(program.nodes.size());
    std::map<std::string, ex> input_value; // a missing value leaves the symbol: not a number
    for (const program_input& in : program.inputs) {
        const auto it = values.find(in.symbol);
        input_value[in.name] = it != values.end() ? it->second : in.symbol;
    }
    for (std::size_t i = 0; i < program.nodes.size(); ++i) {
        const lowered_node& n = program.nodes[i];
        const auto at = [&](int id) { return v[static_cast<std::size_t>(id)]; };
        const ex input = n.k == lowered_node::kind::input ? input_value.at(n.name) : ex();
        const ex r = node_expression(n, input, at);
        v[i] = GiNaC::evalf(r);
    }
    std::vector<numeric> out;
    for (int o : program.outputs) {
        const ex r = v[static_cast<std::size_t>(o)];
        if (!is_a<numeric>(r))
            throw std::logic_error("lower: an output did not evaluate to a number");
        out.push_back(ex_to<numeric>(r));
    }
    return out;
}

} // namespace rotgen
