// rotgen — the part of a run that does not depend on the initial values or the parameter values:
// the derivation, the forms built from it and their kernels, compiled once. `rotgen simulate` runs
// one member on it; `rotgen sweep` runs many, concurrently, on the one prepared scene.
//
// GiNaC is not thread-safe (DESIGN.md: its reference counts and flyweights are unguarded), so
// every use of it after preparation — a form compiled on first use, a member's exact initial
// kinematics — holds symbolic_mutex(), and a member never copies a GiNaC object outside it.
#pragma once

#include "derive/derive.hpp"
#include "run/kernels.hpp"
#include "run/kinematics.hpp"
#include "run/quad_start.hpp"
#include "scene/scene.hpp"
#include "support/timings.hpp"

#include <map>
#include <memory>
#include <mutex>
#include <vector>

namespace rotgen {

// Held by every use of GiNaC that may run beside a member (the one process-wide lock: GiNaC's own
// state is process-wide).
std::mutex& symbolic_mutex();

struct member_values; // run/engine.hpp

// What a member's values give exactly (GiNaC, 30 digits): the initial kinematics, the inertia
// tensor (5.39) and the model's parameter values.
struct member_start {
    initial_kinematics k0;
    Eigen::Matrix3d inertia;
    std::vector<long double> model_parameters;
};

class prepared_scene {
  public:
    // Derives the model and decides what members share: whether the Euler-angle forms can switch
    // to the body form, the default record fitted to the form, the monitored invariants.
    prepared_scene(const scene_spec& scene, stage_timings& timings);
    prepared_scene(const prepared_scene&) = delete;
    prepared_scene& operator=(const prepared_scene&) = delete;

    const scene_spec& scene() const { return m_scene; } // its default record fitted to the form
    // The same method with another tolerance or step (rtol, atol, step, max_steps), what nothing
    // prepared here depends on but the Taylor method's orders (kernels.hpp, taylor_call): so the
    // tuning runs many tolerances on one preparation. std::logic_error for another method or
    // other Taylor orders.
    void retune(const integrator_spec& integrator);
    const derivation& derived() const { return m_d; }
    bool can_switch() const { return m_can_switch; }
    bool orientation() const { return m_orientation; } // the body form keeps the quaternion
    const std::vector<invariant>& invariants() const { return m_invariants; }
    // Whether a run keeps every sample's row (the default) or the last one only: a sweep without
    // trajectories needs no more (its summary takes the last row, and the invariants' drifts are
    // still taken at every sample). A member's rows cost about a quarter of its fixed cost.
    bool every_row() const { return m_every_row; }
    void keep_last_row_only() { m_every_row = false; }

    // The kernels of `form`, compiled (or loaded from the cache) on first use; thread-safe, and the
    // reference stays valid. Throws user_error when the form cannot give a recorded quantity.
    // `*cached` is set false when this call compiled kernels not found in the cache.
    const compiled_form& compiled(form_kind form, stage_timings& timings, bool* cached) const;
    // Compiles now every form a member may use: the scene's, and the body form when it can switch.
    void compile_all(stage_timings& timings) const;
    // A member's exact start, thread-safe: the tensor and parameter values are kept per parameter
    // vector; the kinematics are evaluated in quad precision outside the lock (run/quad_start.hpp),
    // or, for a rotor or without quad precision, by GiNaC under symbolic_mutex() on a scratch
    // copy of the scene kept for it.
    member_start exact_start(const member_values& values) const;

  private:
    const form_expressions& built(form_kind form, bool orientation, stage_timings& timings) const;
    void default_record_follows_form(stage_timings& timings);
    void list_invariants();

    scene_spec m_scene;
    derivation m_d;
    bool m_can_switch = false, m_orientation = false, m_every_row = true;
    std::vector<invariant> m_invariants;
    mutable std::map<std::pair<form_kind, bool>, form_expressions> m_forms; // each built once
    mutable std::map<form_kind, std::unique_ptr<compiled_form>> m_compiled;
    mutable scene_spec m_scratch; // the scene with a member's values (under the lock)
    mutable std::map<std::vector<double>, std::pair<Eigen::Matrix3d, std::vector<long double>>>
        m_by_parameters;
    std::unique_ptr<quad_start> m_quad; // the members' starts without GiNaC, where it can
};

} // namespace rotgen
