// rotgen — run/: `simulate --from` for a gyrostat (continue_from.hpp): each free wheel's momentum
// p_<wheel> (a parameter of the run: derive/wheels.hpp) from the row's column of that name.
#include "run/continue_from.hpp"

#include "scene/initial_input.hpp"
#include "support/error.hpp"
#include "support/format.hpp"

#include <cmath>

namespace rotgen {

void continue_wheels(scene_spec& scene, const start_row& row) {
    if (scene.model.wheels.empty()) return;
    if (scene.form == form_kind::hamiltonian || scene.form == form_kind::reduced)
        throw user_error({row.file, row.line, 1},
                         scene_detail::wheel_momenta_refusal(
                             scene.model, "continue it in the lagrangian or body form"));
    const auto& ps = scene.model.parameters;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        if (!ps[i].wheel_momentum) continue;
        const double v = row_value(row, ps[i].name);
        if (std::isnan(v))
            throw user_error({row.file, row.line, 1},
                             "the row has no column '" + ps[i].name +
                                 "', the free wheel's momentum: record it in the earlier run");
        scene.parameters[i] = v;
        scene.parameters_written[i] = written_value{v, GiNaC::ex(), false};
    }
}

} // namespace rotgen
