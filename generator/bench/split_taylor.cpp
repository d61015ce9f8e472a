// rotgen bench: which of split2/4/6 and taylor the plan runs.
#include "bench/split_taylor.hpp"

#include "emit/emit.hpp"
#include "lower/lower_form.hpp"
#include "run/kernels.hpp"
#include "run/split_run.hpp"
#include "support/error.hpp"

#include <Eigen/Dense>

namespace rotgen::bench {

void check_split(const scene_spec& scene, const GiNaC::exmap& values, split_taylor_methods& m) {
    // the inertia tensor (5.39) at the scene's parameter values, as a run evaluates it
    Eigen::Matrix3d inertia;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            inertia(i, j) =
                GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(scene.model.inertia[i][j].subs(values)))
                    .to_double();
    scene_spec as_split = scene;
    as_split.integrator.method = "split2";
    try {
        check_split_model(as_split, inertia);
    } catch (const user_error& e) {
        m.split_refusal = e.problem();
        return;
    }
    for (int i = 0; i < 3; ++i)
        m.moments[static_cast<std::size_t>(i)] = inertia(i, i);
}

void check_taylor(const model_spec& spec, variant& main, split_taylor_methods& m) {
    const kernel_request request{{"rhs", "taylor"}, main.specialised, {}};
    try {
        emit_header(spec, lower_form(spec, main.f, request), {"rotgen bench", main.unit});
    } catch (const taylor_unsupported& e) {
        m.taylor_refusal = taylor_refusal(spec, e);
        return;
    }
    main.outputs.push_back("taylor");
}

} // namespace rotgen::bench
