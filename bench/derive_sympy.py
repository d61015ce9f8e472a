#!/usr/bin/python3
"""Benchmark: the symbolic stage done by SymPy, for comparison with bench/derive_bench.cpp.

    /usr/bin/python3 bench/derive_sympy.py [--repeats N] [--min-time S] [--format text|tsv] MODEL.yaml...

One timed call reads the model file (YAML, expressions through sympify) and derives, with the same
conventions as rotgen (z-x-z Euler angles, body omega from (5.30), T = 1/2 omega^T I omega (5.38),
V = the potential field plus M g (com . e), e = (sin th sin psi, sin th cos psi, cos th)):

  * the Euler-Lagrange equations with sympy.physics.mechanics.LagrangesMethod
    (form_lagranges_equations), solved for the accelerations (lm.rhs(): LU solve of the mass
    matrix);
  * p = dL/dq_dot, the Hamiltonian H(q, p) = 1/2 l^T I^{-1} l + V with l = J^{-T} p (the same
    structure rotgen uses: J^{-1} written out, I^{-1} by the adjugate, no general inverse of M),
    and Hamilton's equations q_dot = dH/dp, p_dot = -dH/dq.

Models with damping or a torque are refused: LagrangesMethod would need them as forces on
points and frames, which this benchmark does not build. Nothing is simplified (rotgen expands).

A repeat loops the call until at least --min-time seconds have passed (0.2 s; one SymPy call
already takes longer) and divides; median, min and max over --repeats repeats (3 by default).
SymPy's global cache is cleared before every call, so each call starts cold, as a fresh
generator run would (and as rotgen's derivation does: GiNaC keeps no such cache of results).

Output per model: text (default), or tsv for bench/derive.sh:
    model <TAB> median_s <TAB> min_s <TAB> max_s <TAB> calls_per_repeat <TAB> repeats
"""

import argparse
import os
import re
import statistics
import sys
import time

try:
    import sympy as sp
    import yaml
    from sympy.core.cache import clear_cache
    from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols
except ImportError as exc:
    sys.exit("derive_sympy: error: %s (run with /usr/bin/python3; apt-get install python3-sympy "
             "python3-yaml)" % exc)

FUNCTIONS = {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "exp": sp.exp, "log": sp.log,
             "sqrt": sp.sqrt, "abs": sp.Abs, "pow": sp.Pow, "pi": sp.pi, "Pi": sp.pi}
IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
HAMILTONIAN = "structured"  # or "legendre" (--hamiltonian)


def load(path):
    """The model file: its parameters as real Symbols and the inertia and potential in them."""
    with open(path) as f:
        doc = yaml.safe_load(f)
    for key in ("damping", "torque", "body"):
        if key in doc:
            raise SystemExit("derive_sympy: error: %s: '%s' is not supported by this benchmark"
                             % (path, key))
    phi, theta, psi = dynamicsymbols("phi theta psi")
    names = {n: sp.Symbol(n, real=True) for n in (doc.get("parameters") or {})}
    names.update(phi=phi, theta=theta, psi=psi)

    def expr(value):
        text = str(value)
        local = {n: FUNCTIONS.get(n) or names.get(n) or sp.Symbol(n, real=True)
                 for n in set(IDENT.findall(text))}
        return sp.sympify(text, locals=local, convert_xor=True)

    inertia = doc["inertia"]
    if isinstance(inertia[0], list):
        I = sp.Matrix(3, 3, lambda i, j: expr(inertia[i][j]))
        diagonal = all(I[i, j] == 0 for i in range(3) for j in range(3) if i != j)
    else:
        I = sp.diag(*[expr(v) for v in inertia])
        diagonal = True
    V = expr(doc["potential"]) if doc.get("potential") is not None else sp.Integer(0)
    if doc.get("gravity") is not None:
        g = doc["gravity"]
        e = (sp.sin(theta) * sp.sin(psi), sp.sin(theta) * sp.cos(psi), sp.cos(theta))
        V += expr(g["mass"]) * expr(g["g"]) * sum(expr(c) * e[i] for i, c in enumerate(g["com"]))
    return (phi, theta, psi), I, diagonal, V


def derive(path):
    q, I, diagonal, V = load(path)
    phi, theta, psi = q
    t = dynamicsymbols._t
    qd = [x.diff(t) for x in q]
    st, ct, sps, cps = sp.sin(theta), sp.cos(theta), sp.sin(psi), sp.cos(psi)
    J = sp.Matrix([[st * sps, cps, 0], [st * cps, -sps, 0], [ct, 0, 1]])      # (5.30)
    omega = J * sp.Matrix(qd)
    T = (omega.T * I * omega)[0, 0] / 2                                        # (5.38)
    L = T - V

    # Lagrange: LagrangesMethod, then the accelerations from the mass matrix and forcing.
    lm = LagrangesMethod(L, list(q))
    lm.form_lagranges_equations()
    accelerations = lm.rhs()

    # Hamilton: p = dL/dq_dot; H = 1/2 l^T I^{-1} l + V, l = J^{-T} p; q_dot = dH/dp, p_dot = -dH/dq.
    momenta = [sp.diff(L, x) for x in qd]
    p = sp.Matrix(sp.symbols("p_phi p_theta p_psi", real=True))
    Jinv = sp.Matrix([[sps / st, cps / st, 0], [cps, -sps, 0],
                      [-sps * ct / st, -cps * ct / st, 1]])
    Iinv = sp.diag(*[1 / I[i, i] for i in range(3)]) if diagonal else I.adjugate() / I.det()
    if HAMILTONIAN == "legendre":
        # The textbook route instead: q_dot = M^{-1} p by an LU solve, H = p . q_dot - L.
        M = sp.Matrix(3, 3, lambda i, j: sp.diff(momenta[i], qd[j]))
        rates = M.LUsolve(p)
        H = (p.T * rates)[0, 0] - L.subs({qd[i]: rates[i] for i in range(3)})
    else:
        l = Jinv.T * p
        H = (l.T * Iinv * l)[0, 0] / 2 + V
    qdot = [sp.diff(H, x) for x in p]
    pdot = [-sp.diff(H, x) for x in q]
    return accelerations, momenta, H, qdot, pdot


def measure(path, repeats, min_time):
    per_call, calls_max = [], 0
    for _ in range(repeats):
        calls, elapsed = 0, 0.0
        while elapsed < min_time:
            clear_cache()
            start = time.perf_counter()
            derive(path)
            elapsed += time.perf_counter() - start
            calls += 1
        per_call.append(elapsed / calls)
        calls_max = max(calls_max, calls)
    return statistics.median(per_call), min(per_call), max(per_call), calls_max


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("models", nargs="+", metavar="MODEL.yaml")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--min-time", type=float, default=0.2)
    ap.add_argument("--format", choices=["text", "tsv"], default="text")
    ap.add_argument("--hamiltonian", choices=["structured", "legendre"], default="structured",
                    help="H as 1/2 l^T I^-1 l + V, l = J^-T p, as rotgen does (default), or by the "
                         "Legendre transform p.q_dot - L with q_dot = M^-1 p (LU solve)")
    args = ap.parse_args()
    global HAMILTONIAN
    HAMILTONIAN = args.hamiltonian
    if args.repeats < 3:
        ap.error("--repeats must be at least 3")
    if args.format == "text":
        print("SymPy %s: LagrangesMethod + rhs() + Hamiltonian (%s), %d repeats (per call)"
              % (sp.__version__, args.hamiltonian, args.repeats))
    for path in args.models:
        med, lo, hi, calls = measure(path, args.repeats, args.min_time)
        name = os.path.splitext(os.path.basename(path))[0]
        if args.format == "tsv":
            print("%s\t%.9g\t%.9g\t%.9g\t%d\t%d" % (name, med, lo, hi, calls, args.repeats))
        else:
            print("%-22s median %8.3f s   min %8.3f s   max %8.3f s   (%d calls/repeat)"
                  % (name, med, lo, hi, calls))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
