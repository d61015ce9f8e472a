// rotgen runtime — umbrella header: everything a program driving generated models needs.
// Header-only C++17 on Eigen; never includes GiNaC or the generator.
//
//   result.hpp             status, step_stats, integration_result
//   system.hpp             the system concept, lambda_system, generated_system (+ macros)
//   derivatives.hpp        f, ∂f/∂y (analytic or finite differences), ∂f/∂t with counters
//   step_control.hpp       adaptive_options, error norm, PI controller, initial step
//   integrate.hpp          integrate(system, method, t0, y, sample_times, observer)
//   rk4.hpp                classic RK4, fixed step
//   dopri5.hpp             Dormand–Prince 5(4), dense output of order 4
//   dop853.hpp             Dormand–Prince 8(5,3), dense output of order 7
//   implicit_midpoint.hpp  symplectic implicit midpoint rule, Newton with Eigen LU
//   rosenbrock.hpp         RODAS4, L-stable Rosenbrock 4(3) for stiff problems
//   method.hpp             run-time choice of a method by name
//   rotation.hpp           z-x-z Euler angles, passive matrices (5.25), quaternions, angle errors
#pragma once

#include "derivatives.hpp"
#include "dop853.hpp"
#include "dopri5.hpp"
#include "implicit_midpoint.hpp"
#include "integrate.hpp"
#include "method.hpp"
#include "result.hpp"
#include "rk4.hpp"
#include "rosenbrock.hpp"
#include "rotation.hpp"
#include "step_control.hpp"
#include "system.hpp"
