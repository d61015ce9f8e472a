// rotgen bench — the peers, driving the very same generated kernels as rotgen's integrators (the
// variant's rhs and jacobian, inlined in this translation unit, compiled with the same flags).
//
//   Boost.Odeint (state std::array<double, N>, range algebra — Odeint's fast path for small
//   fixed-size systems):
//     dopri5  make_dense_output(tol, tol, runge_kutta_dopri5) with integrate_adaptive
//     rkf78   make_controlled(tol, tol, runge_kutta_fehlberg78) (no dense output: Fehlberg 7(8)
//             has none); with a step: runge_kutta_fehlberg78 alone (fixed steps, like rotgen's
//             DOP853 with a fixed step)
//     rk4     runge_kutta4, the same step as rotgen's rk4
//     rkf78 and rk4 run with integrate_times over the scene's samples, timed and measured alike:
//     without dense output a run that gives the samples must step to each (a step longer than
//     the samples' spacing is cut there), so its error is that of those steps, not of a run to
//     the end alone (which took steps up to the whole span: Fehlberg at tol 1e-3 on the free top,
//     t = 0..100, ended with an energy error of 5e-2 while its run to the samples erred 3e-14).
//     Odeint needs an initial step; it gets the one rotgen's starting-step heuristic (HNW I, II.4)
//     picks for the same tolerance and order, computed outside the timed region.
//     Odeint's error norm is the max-norm of err_i / (tol + tol (|x_i| + dt |dx_i/dt|)), rotgen's
//     the calibrated RMS norm of step_control.hpp (error_layout): equal tolerances are not equal
//     accuracies, which is why the comparison is error against time, not tolerance.
//   SUNDIALS CVODE 6 (serial N_Vector, one SUNContext per configuration):
//     adams   CV_ADAMS with the fixed-point nonlinear solver (the non-stiff setting)
//     bdf     CV_BDF with Newton, the dense linear solver (SUNDenseMatrix + SUNLinSol_Dense) and
//             the generated analytic Jacobian (row-major, copied into the column-major matrix)
//     CVodeSStolerances(tol, tol); CVode(t_k, CV_NORMAL) for each sample t_k (it steps past t_k
//     and interpolates); memory and solvers are created once per configuration, every timed run
//     is CVodeReInit + CVode to each sample. Evaluations are CVODE's own counters
//     (CVodeGetNumRhsEvals + CVodeGetNumLinRhsEvals, CVodeGetNumJacEvals).
//   Every run, timed or not, goes to the scene's samples and stores them (sample_buffer), as
//   rotgen's rows do: the run that is timed is the run that is measured.
#pragma once

#include "run_record.hpp"

#include <boost/numeric/odeint.hpp>

#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace rotgen::bench {

template <class V> struct odeint_rhs {
    using state = std::array<double, V::state_size>;
    const typename V::template params<double>* p;
    std::size_t* count;
    void operator()(const state& x, state& dxdt, double t) const {
        ++*count;
        V::rhs(t, x.data(), dxdt.data(), *p);
    }
};

// Odeint's methods, one bit each (a variant compiles only those its plan uses).
enum odeint_method : unsigned { odeint_dopri5 = 1, odeint_rkf78 = 2, odeint_rk4 = 4 };

// One run of an Odeint method from x (in place) over the sample times `at` (at[0] = t0), calling
// obs(state, t) at each. dopri5 steps on its own and samples its dense output, so its steps are
// those of integrate_adaptive to at.back(); rkf78 and rk4 have no dense output and must step to
// each sample (integrate_times: a step is cut short at a sample), so a run that gives the samples
// takes other steps than one to the end alone, and that is the run both timed and measured.
template <class V, unsigned Method, class State, class Obs>
void odeint_over_times(const odeint_rhs<V>& f, State& x, double tol, double h, double dt0,
                       const std::vector<double>& at, Obs obs) {
    namespace oi = boost::numeric::odeint;
    if constexpr (Method == odeint_dopri5)
        oi::integrate_times(oi::make_dense_output(tol, tol, oi::runge_kutta_dopri5<State>()), f, x,
                            at.begin(), at.end(), dt0, obs);
    else if constexpr (Method == odeint_rkf78) {
        if (h > 0)
            oi::integrate_times(oi::runge_kutta_fehlberg78<State>(), f, x, at.begin(), at.end(), h,
                                obs);
        else
            oi::integrate_times(oi::make_controlled(tol, tol, oi::runge_kutta_fehlberg78<State>()),
                                f, x, at.begin(), at.end(), dt0, obs);
    } else
        oi::integrate_times(oi::runge_kutta4<State>(), f, x, at.begin(), at.end(), h, obs);
}

template <class V, unsigned Method>
run_record run_odeint(const run_spec& spec, double t0, double t1, double dt0,
                      const std::vector<double>& times) {
    using state = std::array<double, V::state_size>;
    struct context {
        typename V::template params<double> p;
        state x0, x;
        std::size_t count = 0;
        std::vector<double> times;
        sample_buffer<double> samples;
    };
    const auto c =
        std::make_shared<context>(context{V::template parameters<double>(),
                                          {},
                                          {},
                                          0,
                                          times,
                                          sample_buffer<double>(times.size(), V::state_size)});
    const auto y0l = V::initial();
    for (std::size_t i = 0; i < V::state_size; ++i)
        c->x0[i] = static_cast<double>(y0l[i]);
    const double tol = spec.tol;
    const long n_steps = spec.step > 0 ? std::lround((t1 - t0) / spec.step) : 1;
    const double h = spec.step > 0 ? (t1 - t0) / double(n_steps) : 0;
    auto once = [c, tol, h, dt0]() -> double {
        const odeint_rhs<V> f{&c->p, &c->count};
        c->x = c->x0;
        c->samples.restart();
        odeint_over_times<V, Method>(f, c->x, tol, h, dt0, c->times,
                                     [&kept = c->samples](const state& y, double) { kept.put(y); });
        return c->x[0];
    };
    run_record rec;
    rec.spec = spec;
    try {
        c->count = 0;
        once();
        rec.rhs_evals = c->count;
        bool finite = true;
        for (double v : c->x) {
            rec.y.push_back(v);
            finite = finite && std::isfinite(v);
        }
        if (!finite) {
            rec.status = "non_finite";
            return rec;
        }
        rec.job.once = once;
        rec.samples = c->samples.rows();
    } catch (const std::exception&) {
        rec.status = "odeint_error";
    }
    return rec;
}

template <class V> struct cvode_user { typename V::template params<double> p; };

template <class V> int cvode_rhs(realtype t, N_Vector y, N_Vector ydot, void* user) {
    const auto* u = static_cast<const cvode_user<V>*>(user);
    V::rhs(double(t), N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), u->p);
    return 0;
}

template <class V>
int cvode_jacobian(realtype t, N_Vector y, N_Vector, SUNMatrix J, void* user, N_Vector, N_Vector,
                   N_Vector) {
    constexpr std::size_t n = V::state_size;
    const auto* u = static_cast<const cvode_user<V>*>(user);
    std::array<double, n * n> rows; // row-major, as generated
    V::jacobian(double(t), N_VGetArrayPointer(y), rows.data(), u->p);
    realtype* cols = SUNDenseMatrix_Data(J); // column-major
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
            cols[j * n + i] = rows[i * n + j];
    return 0;
}

// CVODE's objects for one configuration, freed together.
struct cvode_context {
    SUNContext ctx = nullptr;
    N_Vector y = nullptr, y0 = nullptr;
    void* mem = nullptr;
    SUNMatrix A = nullptr;
    SUNLinearSolver LS = nullptr;
    SUNNonlinearSolver NLS = nullptr;
    int last = 0;
    cvode_context() = default;
    cvode_context(const cvode_context&) = delete;
    cvode_context& operator=(const cvode_context&) = delete;
    ~cvode_context() {
        if (mem) CVodeFree(&mem);
        if (NLS) SUNNonlinSolFree(NLS);
        if (LS) SUNLinSolFree(LS);
        if (A) SUNMatDestroy(A);
        if (y) N_VDestroy(y);
        if (y0) N_VDestroy(y0);
        if (ctx) SUNContext_Free(&ctx);
    }
};

// The CVODE memory of one configuration, with the variant's parameters as user data.
template <class V> struct cvode_variant_context : cvode_context {
    cvode_user<V> user;
    std::vector<double> times;                       // the scene's samples
    sample_buffer<double> samples{0, V::state_size}; // the states there, of the last run
};

// y0 from the variant, CVODE created and set up (BDF with the dense solver and the generated
// Jacobian, or Adams with fixed-point iteration), tolerances spec.tol; the first failing flag.
template <class V>
int cvode_setup(cvode_variant_context<V>& c, bool bdf, const run_spec& spec, double t0) {
    constexpr std::size_t n = V::state_size;
    const auto y0l = V::initial();
    c.y = N_VNew_Serial(static_cast<sunindextype>(n), c.ctx);
    c.y0 = N_VNew_Serial(static_cast<sunindextype>(n), c.ctx);
    for (std::size_t i = 0; i < n; ++i)
        N_VGetArrayPointer(c.y0)[i] = static_cast<double>(y0l[i]);
    N_VScale(1.0, c.y0, c.y);
    c.mem = CVodeCreate(bdf ? CV_BDF : CV_ADAMS, c.ctx);
    int flag = CVodeInit(c.mem, cvode_rhs<V>, t0, c.y);
    if (flag == CV_SUCCESS) flag = CVodeSetUserData(c.mem, &c.user);
    if (flag == CV_SUCCESS) flag = CVodeSStolerances(c.mem, spec.tol, spec.tol);
    if (flag == CV_SUCCESS) flag = CVodeSetMaxNumSteps(c.mem, 100000000L);
    if (flag == CV_SUCCESS) flag = CVodeSetMaxHnilWarns(c.mem, -1);
    if (flag == CV_SUCCESS && bdf) {
        c.A = SUNDenseMatrix(static_cast<sunindextype>(n), static_cast<sunindextype>(n), c.ctx);
        c.LS = SUNLinSol_Dense(c.y, c.A, c.ctx);
        flag = CVodeSetLinearSolver(c.mem, c.LS, c.A);
        if (flag == CV_SUCCESS) flag = CVodeSetJacFn(c.mem, cvode_jacobian<V>);
    } else if (flag == CV_SUCCESS) {
        c.NLS = SUNNonlinSol_FixedPoint(c.y, 0, c.ctx);
        flag = CVodeSetNonlinearSolver(c.mem, c.NLS);
    }
    return flag;
}

// The counters of the last run and its final state into rec.
inline void cvode_counters(const cvode_context& c, bool bdf, std::size_t n, run_record& rec) {
    long nfe = 0, nfels = 0, nje = 0, nst = 0;
    CVodeGetNumRhsEvals(c.mem, &nfe);
    if (bdf) {
        CVodeGetNumLinRhsEvals(c.mem, &nfels);
        CVodeGetNumJacEvals(c.mem, &nje);
    }
    CVodeGetNumSteps(c.mem, &nst);
    rec.rhs_evals = static_cast<std::size_t>(nfe + nfels);
    rec.jac_evals = static_cast<std::size_t>(nje);
    rec.steps = static_cast<std::size_t>(nst);
    for (std::size_t i = 0; i < n; ++i)
        rec.y.push_back(N_VGetArrayPointer(c.y)[i]);
}

// One run from y0 to each sample time `at` (at[0] = t0; CVODE's own steps, interpolated at each
// sample, CV_NORMAL) into `out`; the first failing flag, or CV_SUCCESS.
inline int cvode_over_times(cvode_context& c, const std::vector<double>& at,
                            sample_buffer<double>& out) {
    N_VScale(1.0, c.y0, c.y);
    CVodeReInit(c.mem, at.front(), c.y);
    out.restart();
    const double* y = N_VGetArrayPointer(c.y);
    for (std::size_t i = 0; i < at.size(); ++i) {
        realtype tret = at.front();
        if (i > 0)
            if (const int flag = CVode(c.mem, at[i], c.y, &tret, CV_NORMAL); flag < 0) return flag;
        out.put(y);
    }
    return CV_SUCCESS;
}

template <class V>
run_record run_cvode(const run_spec& spec, double t0, const std::vector<double>& times) {
    run_record rec;
    rec.spec = spec;
    const bool bdf = spec.method == "bdf";
    if (!bdf && spec.method != "adams") {
        rec.status = "unknown_method";
        return rec;
    }
    const auto c = std::make_shared<cvode_variant_context<V>>();
    c->user.p = V::template parameters<double>();
    c->times = times;
    c->samples = sample_buffer<double>(times.size(), V::state_size);
    if (SUNContext_Create(nullptr, &c->ctx) != 0) {
        rec.status = "cvode_context";
        return rec;
    }
    if (const int flag = cvode_setup<V>(*c, bdf, spec, t0); flag != CV_SUCCESS) {
        rec.status = "cvode_setup_" + std::to_string(flag);
        return rec;
    }
    auto once = [c]() -> double {
        c->last = cvode_over_times(*c, c->times, c->samples);
        return N_VGetArrayPointer(c->y)[0];
    };
    once();
    cvode_counters(*c, bdf, V::state_size, rec);
    if (c->last < 0) {
        rec.status = "cvode_flag_" + std::to_string(c->last);
        return rec;
    }
    rec.job.once = once;
    rec.samples = c->samples.rows();
    return rec;
}

} // namespace rotgen::bench
