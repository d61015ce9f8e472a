#include "run/prepared.hpp"

#include "derive/rotor.hpp"
#include "expr/numbers.hpp"
#include "expr/symbols.hpp"
#include "run/engine.hpp"
#include "run/kernels.hpp"
#include "run/rotor_chart.hpp"
#include "run/split_run.hpp"
#include "support/error.hpp"

#include <stdexcept>

namespace rotgen {

std::mutex& symbolic_mutex() {
    static std::mutex m; // the one GiNaC lock, by design (GiNaC is not thread-safe): no state
    return m;
}

prepared_scene::prepared_scene(const scene_spec& scene, stage_timings& timings)
    : m_scene(scene), m_scratch(scene) {
    if (scene.integrator.method == "auto") // tune/ resolves it above the run (resolve_auto)
        throw user_error(scene.integrator_where,
                         "integrator auto is chosen before a run by rotgen simulate, sweep and "
                         "tune (and rotgen.simulate); this caller runs a method it is given");
    const model_spec& spec = m_scene.model;
    m_d = timings.time("derive", spec.name, [&] {
        if (!spec.rotor) return derive(spec);
        derivation d; // a rotor's own (derive/rotor.hpp) is derived with its form
        d.cyclic = derive_rotor(spec).cyclic;
        return d;
    });
    const bool split = is_split_method(m_scene.integrator.method);
    if (split) { // the split methods run the body form: no chart to leave
        m_scene.form = form_kind::body;
        m_scene.switch_chart = false;
    }
    // The chart switch: possible for the Euler-angle forms when the model's body form does not go
    // through the chart itself.
    const form_kind form = m_scene.form;
    m_can_switch = spec.rotor
                       ? rotor_can_switch(m_scene)
                       : m_scene.switch_chart &&
                             (form == form_kind::lagrangian || form == form_kind::hamiltonian) &&
                             !built(form_kind::body, true, timings).uses_euler_chart;
    default_record_follows_form(timings);
    list_invariants();
    m_orientation = m_orientation || split; // the split system's torque needs the attitude
    if (!spec.rotor && quad_start::available()) m_quad = std::make_unique<quad_start>(m_scene, m_d);
}

void prepared_scene::retune(const integrator_spec& integrator) {
    const integrator_spec& mine = m_scene.integrator;
    if (integrator.method != mine.method ||
        (mine.method == "taylor" && taylor_call(integrator) != taylor_call(mine)))
        throw std::logic_error("prepared_scene::retune: another method or other Taylor orders");
    m_scene.integrator = integrator;
}

const form_expressions& prepared_scene::built(form_kind form, bool orientation,
                                              stage_timings& timings) const {
    const auto key = std::make_pair(form, form == form_kind::body && orientation);
    auto it = m_forms.find(key);
    if (it == m_forms.end())
        it = m_forms
                 .emplace(key,
                          timings.time("forms", to_string(form),
                                       [&] {
                                           return build_form(m_scene.model, m_d, form,
                                                             lagrangian_strategy::explicit_inverse,
                                                             key.second);
                                       }))
                 .first;
    return it->second;
}

// Without `record:` the scene records phi, theta, psi and energy; the reduced form has no ignored
// angle to record, so the default keeps only what the form gives (an explicit record is checked
// in compile_form, and an angle the form lacks is an error there).
void prepared_scene::default_record_follows_form(stage_timings& timings) {
    if (!m_scene.record_default || m_scene.form != form_kind::reduced) return;
    const form_expressions& f = built(form_kind::reduced, false, timings);
    for (std::size_t r = m_scene.record.size(); r-- > 0;)
        if (!form_gives(f, m_scene.record[r])) {
            m_scene.record.erase(m_scene.record.begin() + static_cast<std::ptrdiff_t>(r));
            m_scene.record_where.erase(m_scene.record_where.begin() +
                                       static_cast<std::ptrdiff_t>(r));
        }
}

// The energy, and every momentum the derivation found conserved.
void prepared_scene::list_invariants() {
    const model_spec& spec = m_scene.model;
    const bool motors = m_d.wheels.driven || m_d.wheels.torqued; // wheels' motors do work
    m_invariants = {{"energy", !spec.has_damping && !spec.has_torque && !motors}};
    for (int i : m_d.cyclic)
        if (m_scene.form != form_kind::reduced)
            m_invariants.push_back({"p_" + spec.angles.names[i], true});
    m_orientation = needs_orientation(m_scene, m_can_switch) ||
                    (m_scene.form == form_kind::body && m_invariants.size() > 1);
}

const compiled_form& prepared_scene::compiled(form_kind form, stage_timings& timings,
                                              bool* cached) const {
    const std::lock_guard<std::mutex> lock(symbolic_mutex());
    auto it = m_compiled.find(form);
    if (it != m_compiled.end()) return *it->second;
    // The stamp in the compiled source names no path, so the same kernels are compiled once,
    // whatever scene file asks for them.
    const std::string command = "rotgen simulate (kernels of model '" + m_scene.model.name + "')";
    // The body form keeps the quaternion when the chart switches to it; as the scene's own form,
    // when the records or invariants need it.
    const bool orientation = form != m_scene.form || m_orientation;
    auto c = std::make_unique<compiled_form>(compile_form(
        m_scene, built(form, orientation, timings), orientation, m_invariants, command, timings));
    if (cached && !c->lib.was_cached()) *cached = false;
    return *m_compiled.emplace(form, std::move(c)).first->second;
}

member_start prepared_scene::exact_start(const member_values& values) const {
    std::unique_lock<std::mutex> lock(symbolic_mutex());
    m_scratch.angles = values.angles;
    m_scratch.initial_rates = values.initial_rates;
    m_scratch.parameters = values.parameters;
    const model_spec& spec = m_scratch.model;
    member_start start;
    auto it = m_by_parameters.find(values.parameters);
    if (it == m_by_parameters.end()) {
        if (m_by_parameters.size() >= 4096) m_by_parameters.clear(); // bounded memory
        GiNaC::exmap at;
        for (std::size_t i = 0; i < spec.parameters.size(); ++i)
            at[spec.parameters[i].symbol] = float_numeric(values.parameters[i]);
        Eigen::Matrix3d inertia;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const GiNaC::ex v =
                    GiNaC::evalf(spec.inertia[i][j].subs(at, GiNaC::subs_options::no_pattern));
                if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
                    throw std::logic_error("run: expression did not evaluate to a real number");
                inertia(i, j) = GiNaC::ex_to<GiNaC::numeric>(v).to_double();
            }
        std::vector<long double> model_parameters;
        for (const auto& p : spec.parameters)
            model_parameters.push_back(scene_parameter_value(m_scratch, {}, p.name));
        it = m_by_parameters.emplace(values.parameters, std::make_pair(inertia, model_parameters))
                 .first;
    }
    start.inertia = it->second.first;
    start.model_parameters = it->second.second;
    const start_values v{values.angles, values.initial_rates, values.parameters};
    const quad_start::programs* quad = m_quad ? m_quad->programs_for(v) : nullptr;
    if (quad) { // no GiNaC from here on: members start concurrently
        lock.unlock();
        start.k0 = m_quad->kinematics(*quad, v);
        return start;
    }
    start.k0 =
        spec.rotor ? rotor_initial_kinematics(m_scratch) : initial_kinematics_of(m_scratch, m_d);
    return start;
}

void prepared_scene::compile_all(stage_timings& timings) const {
    (void)compiled(m_scene.form, timings, nullptr);
    if (m_can_switch) (void)compiled(other_chart(m_scene.form), timings, nullptr);
}

} // namespace rotgen
