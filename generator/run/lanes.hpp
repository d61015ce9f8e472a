// rotgen — members in lanes: W members of an ensemble integrated together, their right-hand sides
// computed by one SIMD batch kernel (the generated header instantiated on xsimd::batch<double>),
// their steps by the runtime's steppers on a lane system (runtime/lanes.hpp).
//
// The batch kernel is compiled once per sweep into its own cached library, for AVX2 with FMA
// (4 doubles a batch) when the CPU has both (checked at run time), else for the compiler's default
// x86-64 target (SSE2, 2 doubles); with -ffp-contract=off, so that the generated arithmetic rounds
// as the scalar kernel's does and a lane differs from the scalar run only by xsimd's vector sin,
// cos, ... Lanes need rk4, dop853 or taylor (lane_check); with taylor the batch kernel library
// holds the coefficient function on batches too, and the lanes share one order and the smallest
// of their Jorba-Zou steps (runtime/steppers/taylor_lanes.hpp).
//
// Events: each lane watches the scene's events on its own state (the batch's event set holds
// every lane's, located on the batch's interpolant, so a lane's event times are its scalar run's
// up to the lane's own differences); a terminal event ends its lane's run there (the lane stops,
// its later samples are dropped) while the other lanes go on.
//
// What a batch cannot carry runs alone on the scalar path (run_member), from the start, so its
// result is the scalar run's: a member whose start is a user error or that starts in the body
// form (gimbal lock), a lane that would change chart at a sample (|sin theta| < 0.1) or whose f
// stops being finite, and every lane of a batch whose shared integration fails (max_steps, a step
// size underflow).
#pragma once

#include "run/compile_cache.hpp"
#include "run/engine.hpp"
#include "run/prepared.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rotgen {

struct lane_kernels {
    // rhs(w, t, y, dydt, lanes): prepared value, state or rate component c of lane l at
    // [c*lanes + l];
    // lanes a multiple of width
    using kernel = void (*)(const double* p, double t, const double* y, double* dydt,
                            unsigned long lanes);
    // taylor(p, t, c, order, lanes): lane_taylor_system's layout (runtime/lanes.hpp); 1 when
    // every coefficient it wrote is finite, else 0
    using taylor_kernel = int (*)(const double* p, double t, double* c, int order,
                                  unsigned long lanes);
    loaded_library lib;
    kernel rhs = nullptr;
    taylor_kernel taylor = nullptr; // with the Taylor method
    std::size_t width = 1;          // doubles per batch
    std::string arch;               // "avx512+fma", "avx2+fma" or "sse2"
    // rhs reads the prepared values (compiled_form::prepare) by lane, taylor the parameters
    void (*prepare)(const double* v, double* w) = nullptr;
    std::size_t prepared_size = 0;
};

// Throws user_error (at the scene's integrator) when lanes cannot run the scene: a method other
// than rk4, dop853 and taylor. Events that act, time events (`every`) and events that count
// (`after`) do not stop lanes: a member meets one leaves its batch and runs alone (run_lanes).
void lane_check(const scene_spec& scene);

// Whether the lanes run `method` (rk4, dop853, taylor): lane_check's rule, which tune/ follows too.
bool lanes_run(const std::string& method);

// The batch kernel of the scene's form (compiled, or loaded from the cache) for `lanes` members
// run together: a `taylor` scene's is 8 wide where the CPU has AVX-512 and `lanes` is a multiple
// of 8 (unless ROTGEN_LANES_TARGET=avx2; another value of it throws user_error).
lane_kernels compile_lanes(const prepared_scene& prepared, stage_timings& timings,
                           std::size_t lanes);

// Runs the members together; a member's entry is empty when it must run alone: it changes chart,
// an event that acts or counts occurs in its lane, or the scene has a time event (every member).
// Thread-safe as run_member is.
std::vector<std::optional<run_result>> run_lanes(const prepared_scene& prepared,
                                                 const lane_kernels& kernels,
                                                 const std::vector<member_values>& members);

} // namespace rotgen
