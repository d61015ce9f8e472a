// Tests that emit headers as `rotgen emit` does: build the form, lower it, print it.
#pragma once

#include "derive/derive.hpp"
#include "emit/emit.hpp"
#include "lower/lower_form.hpp"
#include "spec/spec.hpp"

#include <string>
#include <vector>

namespace rotgen::test {

// What a test asks of the emitter: the form, the request, the header's options; emitted as
// `rotgen emit` does (build the form, lower it, print it).
struct emit_request {
    form_kind form = form_kind::lagrangian;
    lagrangian_strategy strategy = lagrangian_strategy::explicit_inverse;
    std::vector<std::string> outputs;
    bool specialise_all = false;
    std::vector<std::string> specialise;
    std::vector<std::string> sensitivities; // parameters.<name> keys (emit --sensitivities)
    std::string command;
    std::string name;
};

inline emitted_header emit_with(const model_spec& spec, const derivation& d,
                                const emit_request& o) {
    const kernel_request request{o.outputs, o.specialise_all, o.specialise, o.sensitivities};
    const form_expressions f = build_requested_form(spec, d, o.form, o.strategy, request);
    return emit_header(spec, lower_form(spec, f, request), {o.command, o.name});
}

} // namespace rotgen::test
