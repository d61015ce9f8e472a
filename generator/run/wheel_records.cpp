// rotgen — run/: a gyrostat's recorded quantities (records.hpp; derive/wheels.hpp): with I_e the
// body's inertia (+ J a a^T of rate-driven wheels) and h = sum p_k a_k,
//   L = I_e omega + h (total, body axes),  T = 1/2 omega . I_e omega + h_driven . omega + wheels',
//   h1 h2 h3, p_<wheel> = J (a . omega + <wheel>_dot), <wheel>_dot.
#include "derive/wheels.hpp"
#include "run/records.hpp"

namespace rotgen {

using GiNaC::ex;

namespace {

vector3 omega_of(const std::vector<ex>& w) {
    return {w[0], w[1], w[2]};
}

} // namespace

std::array<ex, 3> gyrostat_momentum(const model_spec& spec, const std::vector<ex>& w) {
    const matrix3 I = gyrostat_inertia(spec);
    const wheel_terms t = wheel_terms_of(spec);
    std::array<ex, 3> l;
    for (std::size_t i = 0; i < 3; ++i) {
        l[i] = t.h[i];
        for (std::size_t j = 0; j < 3; ++j)
            l[i] += I[i][j] * w[j];
    }
    return l;
}

ex gyrostat_kinetic(const model_spec& spec, const std::vector<ex>& w) {
    const matrix3 I = gyrostat_inertia(spec);
    const wheel_terms t = wheel_terms_of(spec);
    ex T = t.kinetic;
    for (std::size_t i = 0; i < 3; ++i) {
        T += t.h_driven[i] * w[i];
        for (std::size_t j = 0; j < 3; ++j)
            T += I[i][j] * w[i] * w[j] / 2;
    }
    return T;
}

std::optional<ex> wheel_record(const model_spec& spec, const std::vector<ex>& w,
                               const std::string& name) {
    const wheel_terms t = wheel_terms_of(spec);
    for (std::size_t i = 0; i < 3; ++i)
        if (name == "h" + std::to_string(i + 1)) return t.h[i];
    const std::vector<ex> p = wheel_momenta(spec, omega_of(w)), r = wheel_rates(spec, omega_of(w));
    for (std::size_t k = 0; k < spec.wheels.size(); ++k) {
        if (name == "p_" + spec.wheels[k].name) return p[k];
        if (name == spec.wheels[k].name + "_dot") return r[k];
    }
    return std::nullopt;
}

} // namespace rotgen
