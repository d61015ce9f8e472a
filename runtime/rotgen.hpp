/// \file
/// rotgen runtime — umbrella header: everything a program driving generated models needs.
/// Header-only C++17 on Eigen; never includes GiNaC or the generator.
///
///   result.hpp                   status, step_stats, integration_result
///   system.hpp                   the system concept, lambda_system, generated_system (+ macros)
///   stepper.hpp                  the method and stepper concepts, is_stepper_v, check_stepper
///   combine.hpp                  the explicit methods' vector arithmetic (work vectors, stages)
///   derivatives.hpp              f, ∂f/∂y (analytic or finite differences), ∂f/∂t with counters
///   step_control.hpp             adaptive_options, error norm, PI controller, initial step
///   steppers/rk4.hpp             classic RK4, fixed step
///   steppers/dopri5.hpp          Dormand–Prince 5(4), dense output of order 4
///   steppers/dop853.hpp          Dormand–Prince 8(5,3), dense output of order 7
///   steppers/implicit_midpoint.hpp  symplectic implicit midpoint rule, Newton with Eigen LU
///   steppers/rosenbrock.hpp      RODAS4, L-stable Rosenbrock 4(3) for stiff problems
///   steppers/taylor.hpp          Taylor method of variable order and step (Jorba–Zou), dense
///                                output from its polynomial; taylor_system.hpp wraps a header
///                                emitted with --outputs rhs,taylor
///   integrate/integrate.hpp      integrate(system, method, t0, y, sample_times, observer)
///                                (fixed.hpp, adaptive.hpp, sampling.hpp, observer.hpp)
///   integrate/events.hpp        event_set: zeros of g(t, y) on the dense output, terminal events
///   integrate/monitor.hpp        invariant_monitor: first value and max drift of invariants
///   integrate/chart_switch.hpp   chart_switch: stop a run near gimbal lock (|sin θ| < threshold)
///   method.hpp                   run-time choice of a method by name
///   rotation.hpp                 z-x-z Euler angles, passive matrices (5.25), quaternions, angle
///   errors
/// (exact_free_top.hpp, the exact free top's ω(t), and free_body/flow.hpp, the exact free
/// rigid-body flow of momentum and attitude, need Boost.Math and are included separately, as are
/// the splitting methods on that flow: steppers/splitting.hpp (split2, split4, split6) with
/// split_system.hpp.)
#pragma once

#include "combine.hpp"
#include "derivatives.hpp"
#include "integrate/chart_switch.hpp"
#include "integrate/events.hpp"
#include "integrate/integrate.hpp"
#include "integrate/monitor.hpp"
#include "integrate/observer.hpp"
#include "lanes.hpp"
#include "method.hpp"
#include "result.hpp"
#include "rotation.hpp"
#include "step_control.hpp"
#include "stepper.hpp"
#include "steppers/dop853.hpp"
#include "steppers/dopri5.hpp"
#include "steppers/implicit_midpoint.hpp"
#include "steppers/rk4.hpp"
#include "steppers/rosenbrock.hpp"
#include "steppers/taylor.hpp"
#include "system.hpp"
#include "taylor_system.hpp"

/// rotgen's runtime (header-only, on Eigen) and, in rotgen::models, the kernels that `rotgen emit`
/// writes: systems, methods and their steppers, the integration driver, events, invariant
/// monitors, lanes, and the rotation conventions (z-x-z Euler angles, passive A, body frame).
namespace rotgen {}
