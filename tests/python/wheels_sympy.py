#!/usr/bin/python3
"""Independent SymPy derivation of a gyrostat (a body with wheels) against `rotgen inspect --format json`.

    /usr/bin/python3 tests/python/wheels_sympy.py --rotgen build/rotgen --model MODEL.yaml

The script reads the model file itself (z-x-z angles, `inertia:` as three moments or a 3x3 matrix,
`wheels:` with free or {rate: ...} drives) and derives with SymPy, never from rotgen's output:

  * A = Az(psi) Ax(theta) Az(phi) (5.25); omega from [omega]x = -A' A^T (5.30);
  * every wheel's angle alpha_k as a coordinate of its own (a function of t), its axis a_k
    normalised, T = 1/2 omega^T I omega + sum 1/2 J_k (a_k . omega + alpha_k')^2, L = T - V;
  * Lagrange's equations for phi, theta, psi and each alpha_k by plain differentiation in time;
  * a free wheel: its equation d/dt dL/d alpha_k' = 0 gives alpha_k'' = -a_k . omega', its
    momentum p_k = dL/d alpha_k' (rotgen's parameter p_<name>) gives alpha_k' = p_k / J_k - a_k .
    omega; a rate drive: alpha_k' = Omega_k(t) given, alpha_k'' = Omega_k'(t);
  * with those put in: the angles' equations, their momenta dL/dq_dot and the total kinetic
    energy T, compared with rotgen's `euler_lagrange`, `momenta` and `kinetic` at random points
    (40 digits, relative 1e-12). Exit 1 on any disagreement, printed with the point.
"""

import argparse
import json
import random
import subprocess
import sys

try:
    import mpmath
    import sympy as sp
    import yaml
except ImportError as exc:  # pragma: no cover
    sys.exit("wheels_sympy: error: %s (run with /usr/bin/python3)" % exc)

DIGITS = 40
RTOL = 1e-12


def rot_z(a):
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[c, s, 0], [-s, c, 0], [0, 0, 1]])


def rot_x(a):
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[1, 0, 0], [0, c, s], [0, -s, c]])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rotgen", required=True)
    ap.add_argument("--model", required=True)
    ap.add_argument("--points", type=int, default=8)
    args = ap.parse_args()
    mpmath.mp.dps = DIGITS
    model = yaml.safe_load(open(args.model))
    out = subprocess.run([args.rotgen, "inspect", args.model, "--format", "json"],
                         capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit("wheels_sympy: rotgen inspect failed: " + out.stderr)
    js = json.loads(out.stdout)

    params = {name: sp.Symbol(name, real=True) for name in js["parameters"]}
    defaults = {params[k]: v for k, v in js["parameters"].items()}
    t = sp.Symbol("t", real=True)
    names = ("phi", "theta", "psi")
    qf = [sp.Function(n)(t) for n in names]
    ns = dict(params)
    ns["t"] = t

    def expr(text):
        return sp.sympify(str(text), locals=ns)

    A = rot_z(qf[2]) * rot_x(qf[1]) * rot_z(qf[0])
    W = -A.diff(t) * A.T
    omega = sp.Matrix([W[2, 1], W[0, 2], W[1, 0]]).applyfunc(sp.simplify)
    inertia = model["inertia"]
    if isinstance(inertia[0], list):
        I = sp.Matrix([[expr(x) for x in row] for row in inertia])
    else:
        I = sp.diag(*[expr(x) for x in inertia])
    T = (omega.T * I * omega)[0] / 2
    wheels = []
    for w in model["wheels"]:
        a = sp.Matrix([expr(x) for x in w["axis"]])
        a = a / sp.sqrt((a.T * a)[0])
        J = expr(w["inertia"])
        drive = w.get("drive", "free")
        alpha = sp.Function("alpha_" + w["name"])(t)
        rate = None if drive == "free" else expr(drive["rate"])
        wheels.append((w["name"], a, J, alpha, rate))
        T += J * ((a.T * omega)[0] + alpha.diff(t)) ** 2 / 2
    V = sp.sympify(str(model.get("potential", 0)), locals={**ns, **dict(zip(names, qf))})
    L = T - V

    # free wheels: alpha' = p/J - a.omega, alpha'' = -a.omega'; rate: Omega(t), Omega'(t)
    subs_dd, subs_d = {}, {}
    for name, a, J, alpha, rate in wheels:
        if rate is None:
            p = sp.Symbol("p_" + name, real=True)
            params.setdefault("p_" + name, p)
            subs_dd[alpha.diff(t, 2)] = -(a.T * omega.diff(t))[0]
            subs_d[alpha.diff(t)] = p / J - (a.T * omega)[0]
        else:
            subs_dd[alpha.diff(t, 2)] = rate.diff(t)
            subs_d[alpha.diff(t)] = rate

    def reduce(e):
        return e.subs(subs_dd).subs(subs_d)

    el = [reduce(L.diff(q.diff(t)).diff(t) - L.diff(q)) for q in qf]
    mom = [reduce(L.diff(q.diff(t))) for q in qf]
    kin = reduce(T)

    # plain symbols for the point
    S = {n: sp.Symbol(n, real=True) for n in names}
    Sd = {n: sp.Symbol(n + "_dot", real=True) for n in names}
    Sdd = {n: sp.Symbol(n + "_ddot", real=True) for n in names}
    plain = {}
    for n, q in zip(names, qf):
        plain[q.diff(t, 2)] = Sdd[n]
    for n, q in zip(names, qf):
        plain[q.diff(t)] = Sd[n]
    for n, q in zip(names, qf):
        plain[q] = S[n]

    def to_plain(e):
        return e.subs(plain)

    el = [to_plain(e) for e in el]
    mom = [to_plain(e) for e in mom]
    kin = to_plain(kin)
    ns_r = {**params, **S, **{k + "_dot": v for k, v in Sd.items()},
            **{k + "_ddot": v for k, v in Sdd.items()}, "t": t}
    r_el = [sp.sympify(s.replace(" = 0", ""), locals=ns_r) for s in js["euler_lagrange"]]
    r_mom = [sp.sympify(s, locals=ns_r) for s in js["momenta"]]
    r_kin = sp.sympify(js["kinetic"], locals=ns_r)

    rng = random.Random(7)
    bad = 0
    for k in range(args.points):
        at = dict(defaults)
        for pname, sym in params.items():
            if pname.startswith("p_") and sym not in at:
                at[sym] = 0
            if k % 2 == 1 or pname.startswith("p_"):
                at[sym] = sp.Float(rng.uniform(0.5, 2.0), DIGITS)
        at[S["theta"]] = sp.Float(rng.uniform(0.2, 2.9), DIGITS)
        for n in ("phi", "psi"):
            at[S[n]] = sp.Float(rng.uniform(0, 6.28), DIGITS)
        for n in names:
            at[Sd[n]] = sp.Float(rng.uniform(-2, 2), DIGITS)
            at[Sdd[n]] = sp.Float(rng.uniform(-2, 2), DIGITS)
        at[t] = sp.Float(rng.uniform(0, 3), DIGITS)
        pairs = [("euler_lagrange[%d]" % i, el[i], r_el[i]) for i in range(3)]
        pairs += [("momenta[%d]" % i, mom[i], r_mom[i]) for i in range(3)]
        pairs.append(("kinetic", kin, r_kin))
        for what, mine, theirs in pairs:
            a = sp.N(mine.subs(at), DIGITS)
            b = sp.N(theirs.subs(at), DIGITS)
            if abs(a - b) > RTOL * max(abs(a), abs(b), 1e-20):
                bad += 1
                print("MISMATCH %s at point %d: sympy %s rotgen %s" % (what, k, a, b))
    print("wheels_sympy: %d points, %d mismatches" % (args.points, bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
