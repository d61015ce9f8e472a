// rotgen — forms/: the torque-driven wheels' momenta as states (derive/wheels.hpp). Each
// torque-driven wheel k appends p_<wheel> to the state, with p_k' = tau_k: its torque with the
// form's own omega, rates and angles put in; the parameter p_<wheel> (its initial value) leaves
// the form's parameters, as the symbol is now a state.
#include "forms/form_algebra.hpp"

#include "expr/symbols.hpp"
#include "support/error.hpp"

namespace rotgen::form_detail {

using GiNaC::ex;

void add_wheel_states(const model_spec& spec, form_expressions& f,
                      const std::function<ex(const ex&)>& in_state) {
    const std::vector<const wheel_spec*> wheels = torque_wheels(spec);
    for (const wheel_spec* w : wheels) {
        f.state.push_back({"p_" + w->name, w->momentum,
                           "axial momentum of the torque-driven wheel " + w->name +
                               ", J (a . omega + " + w->name + "_dot)"});
        f.rates.push_back(in_state(w->drive_value));
        f.rate_names.push_back("p_" + w->name + "_dot");
        for (auto& alternative : f.alternative_rates)
            alternative.push_back(f.rates.back());
    }
    if (wheels.empty()) return;
    std::vector<form_parameter> kept;
    for (const form_parameter& p : f.parameters) {
        bool state = false;
        for (const wheel_spec* w : wheels)
            state = state || p.symbol.is_equal(w->momentum);
        if (!state) kept.push_back(p);
    }
    f.parameters = kept;
    f.notes.push_back("torque-driven wheels: p_<wheel>' = tau (the motor torque about its axis); "
                      "the body feels -tau a.");
}

void refuse_torque_wheels_in(const model_spec& spec, form_kind form) {
    if (form == form_kind::reduced)
        refuse_torque_wheels(spec, "the reduced form",
                             "use the lagrangian, hamiltonian or body form");
}

} // namespace rotgen::form_detail
