#include "run/start_check.hpp"

#include "support/error.hpp"
#include "support/format.hpp"

#include <cmath>
#include <optional>

namespace rotgen {

// Initial values the parser accepts (each finite) may still overflow double precision in what
// the run computes from them: a rate of 1e300 squares to inf in the energy. Before the run: the
// form's state and parameters, f(t0, y0), and the invariants at t0 must be finite — as the kernels
// compute them — or the scene's `initial` is the error.
void check_finite_start(const start_context& c, const initial_kinematics& k,
                        const compiled_form& cf, const std::vector<double>& parameters,
                        const Eigen::VectorXd& y) {
    const scene_spec& scene = c.scene;
    const loaded_system sys = cf.system(parameters);
    // Values far below the overflow threshold cannot overflow a product of a few of them: a
    // non-finite f or invariant is then the model's own singularity (1/(theta - 0.5) at 0.5).
    double largest = y.size() > 0 ? y.cwiseAbs().maxCoeff() : 0;
    for (double v : parameters)
        largest = std::max(largest, std::abs(v));
    for (std::size_t i = 0; k.have_rates && i < 3; ++i)
        for (long double v : {k.qd[i], k.p[i], k.omega[i]})
            largest = std::max(largest, static_cast<double>(std::abs(v)));
    const auto check = [&](const std::string& what, double v, const std::string& in = "") {
        if (std::isfinite(v)) return;
        const std::string value =
            what + " = " + format_number(v) + in + " at t = " + format_double(scene.t_start);
        if (!in.empty() || what == "energy" || what == "V") // what the model computes
            if (largest < 1e50)
                throw user_error(scene.initial_where,
                                 "the model's equations are not finite at the initial state (" +
                                     value +
                                     "): its potential, torque or damping is singular there; "
                                     "start the scene away from that state");
        throw user_error(scene.initial_where,
                         "initial values too large for double precision: " + value +
                             "; give smaller initial rates or momenta, or rescale the model's "
                             "units");
    };
    const auto& q = scene.model.angles.names;
    if (k.have_rates)
        for (std::size_t i = 0; i < 3; ++i) {
            check(q[i] + "_dot", static_cast<double>(k.qd[i]));
            check("p_" + q[i], static_cast<double>(k.p[i]));
            check("omega" + std::to_string(i + 1), static_cast<double>(k.omega[i]));
        }
    const form_expressions& f = cf.f;
    for (std::size_t i = 0; i < f.state.size(); ++i)
        check(f.state[i].name, y[static_cast<Eigen::Index>(i)]);
    for (std::size_t i = 0; i < f.parameters.size(); ++i)
        check(f.parameters[i].name, parameters[i]);
    Eigen::VectorXd dydt(y.size());
    sys.rhs(scene.t_start, y.data(), dydt.data());
    for (std::size_t i = 0; i < f.rate_names.size(); ++i)
        check(f.rate_names[i], dydt[static_cast<Eigen::Index>(i)], " in f(t0, y0)");
    std::vector<double> out(cf.outputs);
    cf.record(parameters.data(), scene.t_start, y.data(), out.data());
    std::optional<std::array<double, 3>> e;
    const std::vector<invariant>& invariants = c.invariants;
    for (std::size_t i = 0; i < invariants.size(); ++i)
        check(invariants[i].name, source_value(c.sequence, cf.invariants[i], y, out, c.inertia, e));
}

} // namespace rotgen
