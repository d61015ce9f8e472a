// The CVODES route of sensitivity_bench.cpp: forward sensitivities of only the key columns (the
// k parameters, plus the n initial values when `initial`), Adams, staggered corrector, S in the
// error test (CVodeSetSensErrCon), fS from the emitted jacobian and parameter_jacobian. Memory is
// created per call (as the other routes build their systems per call).
#pragma once

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <cstddef>
#include <vector>

namespace cvodes_route {

// What the callbacks need: the parameters and which S columns CVODES carries.
template <class U> struct user {
    typename U::P p;
    std::size_t first_column; // 0 with the initial values as keys, else n
};

template <class U> int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* data) {
    U::rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), static_cast<user<U>*>(data)->p);
    return 0;
}

template <class U>
int jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix J, void* data, N_Vector, N_Vector,
             N_Vector) {
    constexpr std::size_t n = U::n;
    double m[n * n];
    U::jacobian(t, N_VGetArrayPointer(y), m, static_cast<user<U>*>(data)->p);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
            SM_ELEMENT_D(J, i, j) = m[i * n + j];
    return 0;
}

template <class U>
int sensitivity_rhs(int count, sunrealtype t, N_Vector y, N_Vector, N_Vector* S, N_Vector* dS,
                    void* data, N_Vector, N_Vector) {
    const auto* u = static_cast<user<U>*>(data);
    constexpr std::size_t n = U::n, k = U::k;
    double J[n * n], D[n * k];
    U::jacobian(t, N_VGetArrayPointer(y), J, u->p);
    U::parameter_jacobian(t, N_VGetArrayPointer(y), D, u->p);
    for (std::size_t c = 0; c < static_cast<std::size_t>(count); ++c) {
        const std::size_t column = u->first_column + c;
        const double* s = N_VGetArrayPointer(S[c]);
        double* d = N_VGetArrayPointer(dS[c]);
        for (std::size_t i = 0; i < n; ++i) {
            double v = column >= n ? D[i * k + (column - n)] : 0.0;
            for (std::size_t j = 0; j < n; ++j)
                v += J[i * n + j] * s[j];
            d[i] = v;
        }
    }
    return 0;
}

// S(t_end), row-major n x (n + k) (the columns CVODES does not carry are 0), from y0 with the
// default parameters at rtol, atol = rtol / 100 (state and S); Newton with the dense solver and
// the emitted Jacobian, or fixed-point iteration (the non-stiff setting, as the work-precision
// bench's CVODE Adams peer). Empty when a CVODES call failed or it did not reach t_end.
template <class U>
std::vector<double> sensitivities(const std::vector<double>& y0, double t_end, double rtol,
                                  bool initial, bool newton) {
    constexpr std::size_t n = U::n, nk = U::n + U::k;
    user<U> u{typename U::P{}, initial ? 0 : n};
    const std::size_t count = nk - u.first_column;
    SUNContext context = nullptr;
    SUNContext_Create(nullptr, &context);
    N_Vector y = N_VNew_Serial(static_cast<sunindextype>(n), context);
    for (std::size_t i = 0; i < n; ++i)
        N_VGetArrayPointer(y)[i] = y0[i];
    void* memory = CVodeCreate(CV_ADAMS, context);
    SUNMatrix A =
        SUNDenseMatrix(static_cast<sunindextype>(n), static_cast<sunindextype>(n), context);
    SUNLinearSolver solver = SUNLinSol_Dense(y, A, context);
    N_Vector* S = N_VCloneVectorArray(static_cast<int>(count), y);
    for (std::size_t c = 0; c < count; ++c) {
        N_VConst(0.0, S[c]);
        if (u.first_column + c < n) N_VGetArrayPointer(S[c])[u.first_column + c] = 1.0;
    }
    std::vector<double> atols(count, rtol / 100);
    bool ok = CVodeInit(memory, rhs<U>, 0.0, y) == CV_SUCCESS;
    ok = ok && CVodeSStolerances(memory, rtol, rtol / 100) == CV_SUCCESS;
    ok = ok && CVodeSetUserData(memory, &u) == CV_SUCCESS;
    ok = ok && CVodeSetLinearSolver(memory, solver, A) == CV_SUCCESS;
    ok = ok && CVodeSetJacFn(memory, jacobian<U>) == CV_SUCCESS;
    ok = ok && CVodeSetMaxNumSteps(memory, 10000000) == CV_SUCCESS;
    ok = ok && CVodeSensInit(memory, static_cast<int>(count), CV_STAGGERED, sensitivity_rhs<U>,
                             S) == CV_SUCCESS;
    SUNNonlinearSolver fixed = SUNNonlinSol_FixedPoint(y, 0, context);
    SUNNonlinearSolver fixed_sens =
        SUNNonlinSol_FixedPointSens(static_cast<int>(count), y, 0, context);
    if (!newton) {
        ok = ok && CVodeSetNonlinearSolver(memory, fixed) == CV_SUCCESS &&
             CVodeSetNonlinearSolverSensStg(memory, fixed_sens) == CV_SUCCESS;
    }
    ok = ok && CVodeSensSStolerances(memory, rtol, atols.data()) == CV_SUCCESS;
    ok = ok && CVodeSetSensErrCon(memory, SUNTRUE) == CV_SUCCESS;
    double t = 0;
    ok = ok && CVode(memory, t_end, y, &t, CV_NORMAL) >= 0 &&
         CVodeGetSens(memory, &t, S) == CV_SUCCESS && t == t_end;
    std::vector<double> out(n * nk, 0.0);
    for (std::size_t c = 0; c < count; ++c)
        for (std::size_t i = 0; i < n; ++i)
            out[i * nk + u.first_column + c] = N_VGetArrayPointer(S[c])[i];
    N_VDestroyVectorArray(S, static_cast<int>(count));
    CVodeFree(&memory);
    SUNLinSolFree(solver);
    SUNMatDestroy(A);
    N_VDestroy(y);
    SUNNonlinSolFree(fixed);
    SUNNonlinSolFree(fixed_sens);
    SUNContext_Free(&context);
    if (!ok) out.clear();
    return out;
}

} // namespace cvodes_route
