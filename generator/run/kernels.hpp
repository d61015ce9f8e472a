// rotgen — one form of a scene's model as running code: its header emitted, compiled into a cached
// shared object and loaded, with a record program that computes the scene's recorded columns and
// monitored invariants from the form's state.
//
// Angles are z-x-z Euler angles (passive A = Az(psi) Ax(theta) Az(phi), 5.25), omega in body axes
// (5.30); the body form's quaternion rotates body axes into space axes.
#pragma once

#include "derive/derive.hpp"
#include "emit/taylor.hpp"
#include "forms/forms.hpp"
#include "run/compile_cache.hpp"
#include "run/taylor_sensitivity.hpp"
#include "scene/scene.hpp"
#include "support/timings.hpp"

#include <euler_sequence.hpp> // runtime
#include <rotgen.hpp>         // runtime

#include <Eigen/Dense>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rotgen {

// A system whose kernels were compiled and loaded at run time (runtime/system.hpp concept), with
// the parameter values `p` it passes to every call (the form's parameter order; set by the run).
struct loaded_system {
    using kernel = void (*)(const double* p, double t, const double* y, double* out);
    // taylor(p, t, c, order), emit/taylor.hpp
    using taylor_kernel = void (*)(const double* p, double t, double* c, int order);
    // f and jac read the prepared values w (the parameters, then the header's hoisted constants:
    // rotgen_prepare); tay reads the parameter values p
    kernel f = nullptr, jac = nullptr;
    taylor_kernel tay = nullptr; // compiled only for a scene integrated by the Taylor method
    std::size_t n = 0, series = 0;
    const double* p = nullptr;
    const double* w = nullptr;
    std::shared_ptr<const std::vector<double>> prepared; // owns w
    std::size_t size() const { return n; }
    void rhs(double t, const double* y, double* dydt) const { f(w, t, y, dydt); }
    void jacobian(double t, const double* y, double* J) const { jac(w, t, y, J); }
    std::size_t taylor_series() const { return series; }
    void taylor(double t, double* c, int order) const { tay(p, t, c, order); }
};

// Where a recorded column (or a monitored invariant) comes from in one compiled form.
struct value_source {
    enum kind_t {
        compiled,             // an output of the compiled record program
        angle,                // body form: Euler angle `index` of the quaternion
        euler_rate,           // body form: q_dot = J^{-1} omega (5.30), undefined at theta = 0, pi
        canonical_momentum,   // body form: p = J^T I omega
        quaternion_of_state,  // body form: component `index` of q / |q|, q0 >= 0
        quaternion_of_angles, // Euler-angle forms: of qz(phi) (x) qx(theta) (x) qz(psi), q0 >= 0
    } kind;
    int index;
    // canonical_momentum of a gyrostat or of a run with sensitivities: where the record program
    // holds the total L1..L3 (I omega + h, run/wheel_records.cpp); -1: I omega.
    int momentum = -1;
};

// A quantity to monitor along the run: the energy, or a momentum the derivation found conserved.
struct invariant {
    std::string name;
    bool conserved;
};

// Immutable once compiled: runs with their own parameter values share it (system(values)).
struct compiled_form {
    form_kind form = form_kind::lagrangian;
    form_expressions f;
    loaded_library lib;
    loaded_system sys;                         // without parameter values (p null)
    loaded_system::kernel record = nullptr;    // record(p, t, y, out): the record program
    std::vector<loaded_system::kernel> events; // g of each scene event, out[0] (event_kernels.hpp)
    // With the scene's sensitivities (else null), (v, t, y, out): the record program's outputs by
    // (y, P), row-major outputs x (n + P) (P: the form's parameters, v as for record)
    loaded_system::kernel record_jacobian = nullptr;
    // With sensitivities, (v, t, y, out): the augmented system (y, S)' (run/variational.hpp)
    loaded_system::kernel variational = nullptr;
    std::vector<loaded_system::kernel> event_jacobians; // g of each event by (y, P, t): n + P + 1
    // A Taylor run with sensitivities (else null): taylor(v, t, c, order) of (y, S), v the
    // parameters then dP/ds at taylor_forcing's inputs (run/taylor_sensitivity.hpp)
    loaded_system::taylor_kernel taylor_sensitivity = nullptr;
    std::size_t taylor_sensitivity_series = 0;
    augmented_forcing taylor_forcing;
    std::vector<value_source> columns;    // one per quantity column (body_x expands to 3)
    std::vector<value_source> invariants; // as the invariants are listed
    std::size_t outputs = 0;              // of the record program
    std::string header, unit; // the emitted header and its unit (lanes compile it for a batch)
    std::string taylor_call;  // the header's function the Taylor entry points call
    // prepare(v, w): w = the parameter values v, then the constants computed from them
    void (*prepare)(const double* v, double* w) = nullptr;
    std::vector<std::string> constants; // the members of w after the parameters: c000, ...
    std::size_t prepared_size() const { return f.parameters.size() + constants.size(); } // of w

    // The system with these parameter values (they must outlive it), prepared once here.
    loaded_system system(const std::vector<double>& values) const {
        loaded_system s = sys;
        s.p = values.data();
        auto w = std::make_shared<std::vector<double>>(prepared_size());
        prepare(values.data(), w->data());
        s.w = w->data();
        s.prepared = std::move(w);
        return s;
    }
};

// The generated function that expands the scene's Taylor series: taylor_specialised<P...> with the
// orders its tolerances give (rotgen::taylor<double>::order_for) compiled as straight-line code.
std::string taylor_call(const integrator_spec& integrator);

// Why the Taylor method cannot run the model (a run's refusal, and `rotgen bench`'s plan): `e`
// from emitting its Taylor coefficients (emit/taylor.hpp).
std::string taylor_refusal(const model_spec& spec, const taylor_unsupported& e);

// The runtime's direction (runtime/integrate/events.hpp) of a scene event.
event_direction direction_of(const event_spec& e);

// Emits, lowers and compiles (or loads from the cache) the built form `f` of the scene's model,
// with the record program for the scene's `record` list and `invariants`, and one function per
// scene event. `command` stamps the
// header. Throws user_error when the form cannot give a recorded quantity.
compiled_form compile_form(const scene_spec& scene, form_expressions f, bool orientation,
                           const std::vector<invariant>& invariants, const std::string& command,
                           stage_timings& timings);

// Whether the form itself gives the quantity `name` (a state, an output or a rate).
bool form_gives(const form_expressions& f, const std::string& name);
// Its expression in the form's state, if the form gives it.
std::optional<GiNaC::ex> form_value(const form_expressions& f, const std::string& name);

// A recorded column or monitored invariant at a sample (t, y): an output `out` of the form's
// record program, or in the body form from the quaternion and omega: the Euler angles, their
// rates q_dot = J^{-1} omega (5.30, undefined at theta = 0, pi), p = J^T I omega; or the unit
// quaternion of the attitude (body -> space, scalar first, the sign with q0 >= 0: the same in
// every form and across a chart switch), all in the model's sequence s. `e` caches the angles
// between calls at one sample.
double source_value(const euler_sequence& s, const value_source& src,
                    Eigen::Ref<const Eigen::VectorXd> y, const std::vector<double>& out,
                    const Eigen::Matrix3d& inertia, std::optional<std::array<double, 3>>& e);

} // namespace rotgen
