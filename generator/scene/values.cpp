// rotgen — scene/: parameter overrides and initial values as numbers or expressions (values.hpp).
#include "scene/values.hpp"

#include "expr/numbers.hpp"
#include "lower/lower_form.hpp" // exact_decimal

#include <cmath>

namespace rotgen::scene_detail {

using GiNaC::ex;

double scene_number(const YAML::Node& n, const std::string& file, const std::string& what) {
    const source_location where = location_of(n, file);
    if (!n.IsScalar() || !is_decimal(n.Scalar()))
        throw user_error(where, what + " must be a finite number");
    const double v = std::strtod(n.Scalar().c_str(), nullptr);
    if (!std::isfinite(v)) throw user_error(where, what + " must be a finite number");
    // GiNaC::numeric(double) throws CLN's underflow exception on a subnormal number.
    if (std::fpclassify(v) == FP_SUBNORMAL)
        throw user_error(where, what + " must be 0 or at least 2.2e-308 in magnitude");
    return v;
}

namespace {

// YAML's own spellings of the special floats: not numbers, and not expressions either.
bool yaml_special_float(const std::string& s) {
    std::string t;
    for (char c : s)
        t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* special : {".nan", ".inf", "+.inf", "-.inf", "nan", "inf", "-inf", "+inf"})
        if (t == special) return true;
    return false;
}

bool written_as_number(const YAML::Node& n) {
    return !n.IsScalar() || is_decimal(n.Scalar()) || yaml_special_float(n.Scalar());
}

} // namespace

value_reader::value_reader(const std::string& file, const model_spec& model)
    : m_file(file), m_model(model), m_names(model.parameter_names()) {}

// A number as scene_number reads it; an expression exact, with the parameters' exact values put
// in, its double the value at 40 digits rounded once (CLN rounds to nearest).
written_value value_reader::evaluate(const YAML::Node& n, const std::string& what,
                                     const GiNaC::exmap& values) const {
    written_value w;
    if (written_as_number(n)) {
        w.value = scene_number(n, m_file, what);
        return w;
    }
    const ex e = parse_expression(n.Scalar(), m_names, at(n), what).subs(values);
    const std::string problem = what + " = " + n.Scalar();
    GiNaC::numeric v;
    try {
        const scoped_digits digits(40);
        const ex e40 = GiNaC::evalf(e);
        if (!GiNaC::is_a<GiNaC::numeric>(e40) || !GiNaC::ex_to<GiNaC::numeric>(e40).is_real())
            throw user_error(at(n), problem + " is not a real number");
        v = GiNaC::ex_to<GiNaC::numeric>(e40);
    } catch (const user_error&) {
        throw;
    } catch (const std::exception&) { // CLN cannot evaluate it (an overflow)
        throw user_error(at(n), problem + " is not a finite double");
    }
    const GiNaC::numeric a = GiNaC::abs(v);
    if (a > GiNaC::numeric("1.7976931348623157e308"))
        throw user_error(at(n), problem + " is not a finite double");
    if (!a.is_zero() && a < GiNaC::numeric("2.2250738585072014e-308"))
        throw user_error(at(n), problem + " must be 0 or at least 2.2e-308 in magnitude");
    const double x = v.to_double(); // CLN rounds to nearest
    w.value = x;
    w.exact = e;
    w.expression = true;
    return w;
}

void value_reader::resolve(std::size_t i, const YAML::Node& overrides) {
    const parameter& p = m_model.parameters[i];
    if (m_state[i] == 2) return;
    if (!overrides || !overrides[p.name]) {
        m_values[i].value = p.value;
    } else {
        const YAML::Node n = overrides[p.name];
        if (m_state[i] == 1)
            throw user_error(at(n), "parameter '" + p.name + "' is defined in terms of itself");
        m_state[i] = 1;
        const std::string what = "parameter '" + p.name + "'";
        if (!written_as_number(n)) {
            const ex e = parse_expression(n.Scalar(), m_names, at(n), what);
            for (std::size_t j = 0; j < m_model.parameters.size(); ++j)
                if (e.has(m_model.parameters[j].symbol)) resolve(j, overrides);
        }
        m_values[i] = evaluate(n, what, m_exact);
    }
    m_exact[p.symbol] =
        m_values[i].expression ? m_values[i].exact : ex(exact_decimal(m_values[i].value));
    m_state[i] = 2;
}

std::vector<written_value> value_reader::parameters(const YAML::Node& overrides) {
    m_values.assign(m_model.parameters.size(), written_value{});
    m_state.assign(m_model.parameters.size(), 0);
    m_exact.clear();
    for (std::size_t i = 0; i < m_model.parameters.size(); ++i)
        resolve(i, overrides);
    return m_values;
}

written_value value_reader::value(const YAML::Node& n, const std::string& what) const {
    return evaluate(n, what, m_exact);
}

} // namespace rotgen::scene_detail
