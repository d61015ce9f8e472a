// rotgen — the variational system of a form, and its compiled entry point (run/variational.hpp).
#include "run/variational.hpp"

#include "emit/printer.hpp"
#include "lower/lower.hpp"

#include <sstream>

namespace rotgen {

namespace {

using GiNaC::ex;

// A term of S'_ij: the local holding its factor (empty: the factor is exactly 1) and the entry of
// S or D it multiplies, printed with the column index rgv_j.
struct product_term {
    std::string factor, entry;
};

std::string entry(const std::string& array, std::size_t row, std::size_t k) {
    return array + "[" + std::to_string(row * k) + " + rgv_j]";
}

// The state as y[i], the parameters as v[i] (named rg_<name>: no clash with the kernel's own
// names, rgv_*, whatever a parameter is called), the time t.
std::vector<program_input> inputs_of(const form_expressions& f) {
    std::vector<program_input> in;
    for (std::size_t i = 0; i < f.state.size(); ++i)
        in.push_back({f.state[i].symbol, f.state[i].name, "y[" + std::to_string(i) + "]"});
    for (std::size_t i = 0; i < f.parameters.size(); ++i)
        in.push_back({f.parameters[i].symbol, "rg_" + f.parameters[i].name,
                      "v[" + std::to_string(i) + "]", f.parameters[i].specialisable});
    in.push_back({f.time, "t", ""});
    return in;
}

// The factors of one block (d f/d y by S, or d f/d P by D) of S' = (d f/d y) S + (d f/d P) D:
// its non-zero entries, an entry other than 1 appended to `program` and its name rgv_<name>_i_m to
// `locals`, in the same order.
void add_block(const std::vector<ex>& block, std::size_t columns, const std::string& name,
               const std::string& array, std::size_t k, std::vector<ex>& program,
               std::vector<std::string>& locals, std::vector<std::vector<product_term>>& rows) {
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t m = 0; m < columns; ++m) {
            const ex& e = block[i * columns + m];
            if (e.is_zero()) continue;
            std::string local;
            if (!e.is_equal(ex(1))) {
                local = "rgv_" + name + "_" + std::to_string(i) + "_" + std::to_string(m);
                program.push_back(e);
                locals.push_back(local);
            }
            rows[i].push_back({local, entry(array, m, k)});
        }
}

} // namespace

variational_system variational_system_of(const form_expressions& f) {
    std::vector<ex> parameters;
    for (const auto& p : f.parameters)
        parameters.push_back(p.symbol);
    return {f.rates, jacobian(f), parameter_jacobian(f, f.rates, parameters)};
}

std::vector<ex> augmented_rates(const variational_system& v, const std::vector<ex>& S,
                                const std::vector<ex>& D) {
    const std::size_t n = v.rates.size(), np = n == 0 ? 0 : v.dfdp.size() / n,
                      k = n == 0 ? 0 : S.size() / n;
    std::vector<ex> out = v.rates;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < k; ++j) {
            ex d = 0;
            for (std::size_t m = 0; m < n; ++m)
                d += v.dfdy[i * n + m] * S[m * k + j];
            for (std::size_t p = 0; p < np; ++p)
                d += v.dfdp[i * np + p] * D[p * k + j];
            out.push_back(d);
        }
    return out;
}

std::string variational_entry(const form_expressions& f, std::size_t k) {
    const variational_system vs = variational_system_of(f);
    const std::size_t n = vs.rates.size(), np = f.parameters.size();
    std::vector<ex> program = vs.rates; // f, then the factors in the order add_block meets them
    std::vector<std::string> locals;    // of program[n...]
    std::vector<std::vector<product_term>> rows(n);
    add_block(vs.dfdy, n, "J", "rgv_S", k, program, locals, rows);
    add_block(vs.dfdp, np, "F", "rgv_D", k, program, locals, rows);
    const lowered_program lowered = lower(program, inputs_of(f));
    const std::vector<bool> used = used_inputs(lowered);
    std::ostringstream c;
    c << "\n// (y, S)' = (f, (d f/d y) S + (d f/d P) D), S = dy/ds row-major " << n << " x " << k
      << " after y, D = dP/ds row-major " << np << " x " << k << " after the parameters in v\n"
      << "extern \"C\" void rotgen_variational(const double* v, double t, const double* y, "
         "double* out) {\n    using namespace std;\n    (void)t;\n";
    for (std::size_t i = 0; i < lowered.inputs.size(); ++i)
        if (used[i] && !lowered.inputs[i].definition.empty())
            c << "    const double " << lowered.inputs[i].name << " = "
              << lowered.inputs[i].definition << ";\n";
    for (const auto& step : lowered.steps)
        c << "    const double " << step.name << " = "
          << print_definition(lowered, step.node, "double") << ";\n";
    for (std::size_t o = 0; o < program.size(); ++o)
        c << (o < n ? "    out[" + std::to_string(o) + "]" : "    const double " + locals[o - n])
          << " = " << print_node(lowered, lowered.outputs[o], "double") << ";\n";
    c << "    const double* rgv_S = y + " << n << ";\n    const double* rgv_D = v + " << np
      << ";\n    double* rgv_dS = out + " << n << ";\n    (void)rgv_S;\n    (void)rgv_D;\n"
      << "    for (unsigned long rgv_j = 0; rgv_j < " << k << "; ++rgv_j) {\n";
    for (std::size_t i = 0; i < n; ++i) {
        std::string sum;
        for (const product_term& t : rows[i])
            sum +=
                (sum.empty() ? "" : " + ") + (t.factor.empty() ? "" : t.factor + " * ") + t.entry;
        c << "        rgv_dS[" << i * k << " + rgv_j] = " << (sum.empty() ? "0.0" : sum) << ";\n";
    }
    c << "    }\n}\n";
    return c.str();
}

} // namespace rotgen
