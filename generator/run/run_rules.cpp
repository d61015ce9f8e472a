// rotgen — rules of run/engine.hpp that simulate and bench share (the sample times, whether the
// body form keeps the attitude) and those of run/run_rules.hpp.
#include "run/run_rules.hpp"

#include "run/engine.hpp"

namespace rotgen {

std::vector<double> sample_times(const scene_spec& scene) {
    if (!scene.sample_at.empty()) return scene.sample_at; // fit: the measurement times
    std::vector<double> times(static_cast<std::size_t>(scene.samples));
    for (std::size_t i = 0; i < times.size(); ++i)
        times[i] = i + 1 == times.size() ? scene.t_end
                                         : scene.t_start + (scene.t_end - scene.t_start) *
                                                               double(i) / double(times.size() - 1);
    return times;
}

bool needs_orientation(const scene_spec& scene, bool chart_switch) {
    bool orientation = chart_switch;
    const auto& q = scene.model.angles.names;
    for (const auto& name : scene.record)
        orientation = orientation || name == q[0] || name == q[1] || name == q[2] ||
                      name.rfind("body_", 0) == 0 || name.find("_dot") != std::string::npos ||
                      name.rfind("p_", 0) == 0 || (name.size() == 2 && name[0] == 'q') ||
                      name == "Lx" || name == "Ly" || name == "Lz";
    for (const event_spec& e : scene.events) // an action forms the state from the attitude
        orientation = orientation || e.acts();
    return orientation;
}

bool reached_end(const scene_spec& scene, double t) {
    return scene.t_end >= scene.t_start ? t >= scene.t_end : t <= scene.t_end;
}

void add_stats(step_stats& s, const step_stats& more) {
    s.steps += more.steps, s.accepted += more.accepted, s.rejected += more.rejected;
    s.rhs_evals += more.rhs_evals, s.jac_evals += more.jac_evals,
        s.factorisations += more.factorisations;
}

} // namespace rotgen
