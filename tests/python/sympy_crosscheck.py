#!/usr/bin/python3
"""Independent SymPy cross-check of `rotgen inspect MODEL.yaml --format json`.

Run with Debian's interpreter (python3-sympy, python3-yaml; mpmath comes with sympy):

    /usr/bin/python3 tests/python/sympy_crosscheck.py --rotgen build/rotgen \
        --model models/full_tensor_top.yaml

The script reads the model file itself and derives everything with SymPy, never from rotgen's
output:

  * the passive rotation A = Az(psi) Ax(theta) Az(phi) (5.25, 5.8, 5.9); the body angular velocity
    from [omega]x = -A' A^T, checked symbolically against the chapter's (5.30);
  * T = 1/2 omega^T I omega (5.38) for the model's body-axes tensor, V = the `potential:` field plus
    M g (com . e), e = A's third column (the space vertical in body axes); L = T - V;
  * p = dL/dq_dot, M = dp/dq_dot;  Q = -c .* q_dot + J^T tau with J = d omega / d q_dot;
  * Lagrange's equations by plain differentiation in time of functions phi(t), theta(t), psi(t):
    EL_i = d/dt dL/dq_dot_i - dL/dq_i - Q_i  (the quantity rotgen prints, "= 0");
  * the Hamiltonian side numerically from M: for a momentum p, q_dot = M^{-1} p,
    H = 1/2 p^T M^{-1} p + V and -dH/dq_k = 1/2 q_dot^T (dM/dq_k) q_dot - dV/dq_k, so
    p_dot = -dH/dq + Q(q, q_dot, t);
  * cyclic coordinates: those with dL/dq_i and Q_i identically zero (at every sample point).

rotgen's strings are parsed with sympy.sympify, every identifier bound to a real Symbol (so `I1`,
`E`, `S`, `N`, `beta`, `gamma` are never SymPy built-ins), and both sides are evaluated in 40-digit
arithmetic (mpmath) at random points: angles with theta in [0.2, pi - 0.2], random rates,
accelerations, momenta and time; half the points with the parameters at the defaults the JSON
reports, half with random parameter values. Two values agree when they differ by at most 1e-12
relative to the larger, or by at most 1e-25 absolutely (a zero, at 40 digits). Any disagreement is printed with the
quantity, the point and both values, and the exit status is 1 (2 for a bad invocation or model).
"""

import argparse
import json
import math
import random
import re
import subprocess
import sys

try:
    import mpmath
    import sympy as sp
    import yaml
except ImportError as exc:  # pragma: no cover - environment problem, reported plainly
    sys.exit("sympy_crosscheck: error: %s (run with /usr/bin/python3; apt-get install "
             "python3-sympy python3-yaml)" % exc)

RTOL = 1e-12
ATOL = 1e-25  # evaluation carries 40 digits; anything this small is a zero
DIGITS = 40

COORDS = ("phi", "theta", "psi")
RATES = tuple(c + "_dot" for c in COORDS)
ACCELS = tuple(c + "_ddot" for c in COORDS)
MOMENTA = tuple("p_" + c for c in COORDS)
MODEL_KEYS = {"name", "description", "angles", "parameters", "inertia", "body", "potential",
              "gravity", "damping", "torque"}
AXES = (2, 0, 2)  # the model's sequence a-b-c (0 = x, 1 = y, 2 = z); set by use_angles()


def use_angles(doc):
    """The model's `angles:` (default z-x-z phi, theta, psi; zyx defaults to yaw, pitch, roll):
    sets AXES and the coordinate names COORDS, RATES, ACCELS, MOMENTA."""
    global AXES, COORDS, RATES, ACCELS, MOMENTA
    spec = doc.get("angles", "zxz")
    seq = spec["sequence"] if isinstance(spec, dict) else spec
    AXES = tuple("xyz".index(c) for c in seq)
    names = ("yaw", "pitch", "roll") if seq == "zyx" else ("phi", "theta", "psi")
    if isinstance(spec, dict) and "names" in spec:
        names = tuple(spec["names"])
    COORDS = names
    RATES = tuple(c + "_dot" for c in COORDS)
    ACCELS = tuple(c + "_ddot" for c in COORDS)
    MOMENTA = tuple("p_" + c for c in COORDS)
# Names rotgen's expression language and SymPy share; every other identifier is a Symbol.
FUNCTIONS = {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "asin": sp.asin, "acos": sp.acos,
             "atan": sp.atan, "atan2": sp.atan2, "sinh": sp.sinh, "cosh": sp.cosh,
             "tanh": sp.tanh, "exp": sp.exp, "log": sp.log, "sqrt": sp.sqrt, "abs": sp.Abs,
             "pow": sp.Pow, "pi": sp.pi, "Pi": sp.pi}
IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


class ModelError(Exception):
    """A model file this checker cannot read (exit status 2)."""


class SymbolTable:
    """One real Symbol per name: the model's expressions and rotgen's strings share them."""

    def __init__(self):
        self.table = {}

    def __getitem__(self, name):
        if name not in self.table:
            self.table[name] = sp.Symbol(name, real=True)
        return self.table[name]

    def parse(self, text, allowed, what):
        """Parses `text` (rotgen's output or a model expression) with every identifier that is not
        a known function bound to our Symbol; fails if a symbol outside `allowed` appears."""
        text = str(text)
        local = {}
        for name in set(IDENTIFIER.findall(text)):
            local[name] = FUNCTIONS[name] if name in FUNCTIONS else self[name]
        try:
            expr = sp.sympify(text, locals=local, convert_xor=True)
        except (sp.SympifyError, SyntaxError, TypeError) as exc:
            raise ModelError("%s: cannot parse %r: %s" % (what, text, exc))
        stray = sorted(s.name for s in expr.free_symbols if s.name not in allowed)
        if stray:
            raise ModelError("%s: unexpected symbol(s) %s in %r" % (what, ", ".join(stray), text))
        return expr


# ---------------------------------------------------------------------------------------------
# The model file and SymPy's own derivation
# ---------------------------------------------------------------------------------------------

def number(value, what):
    try:
        return float(str(value))  # PyYAML reads `1e-3` (no dot) as a string
    except ValueError:
        raise ModelError("%s: %r is not a number" % (what, value))


def read_model(path):
    try:
        with open(path) as f:
            doc = yaml.safe_load(f)
    except (OSError, yaml.YAMLError) as exc:
        raise ModelError("%s: %s" % (path, exc))
    if not isinstance(doc, dict):
        raise ModelError("%s: not a YAML mapping" % path)
    unknown = set(doc) - MODEL_KEYS
    if unknown:
        raise ModelError("%s: unknown keys %s" % (path, sorted(unknown)))
    if "body" in doc:
        raise ModelError("%s: 'body' (inertia from parts) is not supported by this checker" % path)
    params = {}
    for name, value in (doc.get("parameters") or {}).items():
        if isinstance(value, dict):
            value = value.get("value")
        params[str(name)] = number(value, "%s: parameter %s" % (path, name))
    return doc, params


def rotation(alpha, beta, gamma, reverse=False):
    """Passive A = A_c(gamma) A_b(beta) A_a(alpha) for the sequence AXES = a-b-c, body <- space;
    Az(psi) Ax(theta) Az(phi) for z-x-z (5.25, 5.8, 5.9). `reverse`: the product in the wrong
    order (a deliberate error)."""
    def elementary(n, a):
        c, s = sp.cos(a), sp.sin(a)
        return [sp.Matrix([[1, 0, 0], [0, c, s], [0, -s, c]]),    # Ax (5.9)
                sp.Matrix([[c, 0, -s], [0, 1, 0], [s, 0, c]]),    # Ay
                sp.Matrix([[c, s, 0], [-s, c, 0], [0, 0, 1]])][n]  # Az (5.8)

    m = [elementary(AXES[0], alpha), elementary(AXES[1], beta), elementary(AXES[2], gamma)]
    return m[0] * m[1] * m[2] if reverse else m[2] * m[1] * m[0]


class Derivation:
    """Everything SymPy derives from the model file (expressions in our symbols)."""

    def __init__(self, doc, params, syms, inject=None):
        q = [syms[n] for n in COORDS]
        qd = [syms[n] for n in RATES]
        qdd = [syms[n] for n in ACCELS]
        t = syms["t"]
        pnames = set(params)
        angles = pnames | set(COORDS)
        forces = angles | set(RATES) | {"t"}

        def expr(value, allowed, what):
            return syms.parse(value, allowed, what)

        # omega from the rotation itself: A(t) = A(q(t)), [omega]x = -A' A^T (body frame).
        fq = [sp.Function(n)(t) for n in COORDS]
        A_t = rotation(*fq, reverse=inject == "sequence-order")
        W = -(A_t.diff(t) * A_t.T)
        back1 = {**{fq[i].diff(t): qd[i] for i in range(3)}, **{fq[i]: q[i] for i in range(3)}}
        omega_A = [W[2, 1].xreplace(back1), W[0, 2].xreplace(back1), W[1, 0].xreplace(back1)]
        st, ct, sps, cps = sp.sin(q[1]), sp.cos(q[1]), sp.sin(q[2]), sp.cos(q[2])
        omega = [qd[0] * st * sps + qd[1] * cps,          # (5.30)
                 qd[0] * st * cps - qd[1] * sps,
                 qd[0] * ct + qd[2]]
        pythagoras = {sp.sin(a) ** 2: 1 - sp.cos(a) ** 2 for a in q}
        for i in range(3 if AXES == (2, 0, 2) else 0):
            if sp.expand(sp.expand(omega_A[i] - omega[i]).subs(pythagoras)) != 0:
                raise AssertionError("omega%d from -A'A^T differs from (5.30): %s vs %s"
                                     % (i + 1, omega_A[i], omega[i]))
        self.omega = sp.Matrix(omega if AXES == (2, 0, 2) else omega_A)

        # Inertia tensor in body axes (5.39 sign convention when given in full).
        inertia = doc.get("inertia")
        if not isinstance(inertia, list) or len(inertia) != 3:
            raise ModelError("inertia must be a list of three moments or a 3x3 matrix")
        if isinstance(inertia[0], list):
            I = sp.Matrix(3, 3, lambda i, j: expr(inertia[i][j], pnames, "inertia"))
            if any(sp.expand(I[i, j] - I[j, i]) != 0 for i in range(3) for j in range(3)):
                raise ModelError("inertia is not symmetric")
        else:
            I = sp.diag(*[expr(v, pnames, "inertia") for v in inertia])
        if inject == "product-sign":  # a deliberate error: products of inertia with the wrong sign
            I = sp.Matrix(3, 3, lambda i, j: I[i, j] if i == j else -I[i, j])
        self.inertia = I

        # T = 1/2 omega^T I omega (5.38)
        self.T = (self.omega.T * I * self.omega)[0, 0] / 2

        # V: the potential field plus uniform gravity M g (com . e), e = A e_z (third column of A)
        V = sp.Integer(0)
        if doc.get("potential") is not None:
            V += expr(doc["potential"], angles, "potential")
        if doc.get("gravity") is not None:
            g = doc["gravity"]
            e = rotation(*q, reverse=inject == "sequence-order")[:, 2]
            com = [expr(v, pnames, "gravity com") for v in g["com"]]
            V += (expr(g["mass"], pnames, "gravity mass") * expr(g["g"], pnames, "gravity g")
                  * sum(com[i] * e[i] for i in range(3)))
        self.V = V
        self.L = self.T - self.V
        self.E = self.T + self.V

        self.p = [sp.diff(self.L, qd[i]) for i in range(3)]
        self.M = sp.Matrix(3, 3, lambda i, j: sp.diff(self.p[i], qd[j]))
        self.dM = [self.M.diff(q[k]) for k in range(3)]
        self.dV = [sp.diff(self.V, q[k]) for k in range(3)]
        self.dLdq = [sp.diff(self.L, q[k]) for k in range(3)]

        # Q = -c .* q_dot + J^T tau, J = d omega / d q_dot (virtual work tau . J dq)
        damping = doc.get("damping")
        if damping is None:
            c = [0, 0, 0]
        elif isinstance(damping, list):
            c = [expr(v, pnames, "damping") for v in damping]
        else:
            c = [expr(damping, pnames, "damping")] * 3
        tau = [expr(v, forces, "torque") for v in (doc.get("torque") or [0, 0, 0])]
        J = self.omega.jacobian(qd)
        Q = [-c[i] * qd[i] + sum(J[k, i] * tau[k] for k in range(3)) for i in range(3)]
        if inject == "force-sign":  # a deliberate error: the generalised force with the wrong sign
            Q = [-x for x in Q]
        self.Q = Q

        # Lagrange's equations by differentiating in time along q(t):
        # EL_i = d/dt dL/dq_dot_i - dL/dq_i - Q_i
        to_t = {**{qd[i]: fq[i].diff(t) for i in range(3)}, **{q[i]: fq[i] for i in range(3)}}
        back2 = {**{fq[i].diff(t, 2): qdd[i] for i in range(3)}, **back1}
        L_t = self.L.xreplace(to_t)
        self.EL = []
        for i in range(3):
            el = sp.diff(sp.diff(L_t, fq[i].diff(t)), t) - sp.diff(L_t, fq[i])
            self.EL.append(el.xreplace(back2) - Q[i])


# ---------------------------------------------------------------------------------------------
# Numerical comparison
# ---------------------------------------------------------------------------------------------

def fmt(x):
    return mpmath.nstr(x, 17)


def agree(a, b):
    d = abs(a - b)
    return d <= RTOL * max(abs(a), abs(b)) or d <= ATOL


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rotgen", required=True, help="the rotgen executable")
    ap.add_argument("--model", required=True, help="the model file (YAML)")
    ap.add_argument("--points", type=int, default=24,
                    help="points per parameter set (defaults, random); default 24")
    ap.add_argument("--seed", type=int, default=20240605)
    ap.add_argument("--inject-error", choices=["force-sign", "product-sign", "sequence-order"],
                    help="derive with a deliberate error, to show that the check fails")
    args = ap.parse_args()
    mpmath.mp.dps = DIGITS

    try:
        doc, file_params = read_model(args.model)
    except ModelError as exc:
        print("sympy_crosscheck: error: %s" % exc, file=sys.stderr)
        return 2
    use_angles(doc)

    run = subprocess.run([args.rotgen, "inspect", args.model, "--format", "json"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        how = ("was killed by signal %d" % -run.returncode if run.returncode < 0
               else "exited with status %d" % run.returncode)
        print("sympy_crosscheck: error: %s inspect %s --format json %s:\n%s"
              % (args.rotgen, args.model, how, run.stderr), file=sys.stderr)
        return 1
    try:
        out = json.loads(run.stdout)
    except json.JSONDecodeError as exc:
        print("sympy_crosscheck: error: rotgen's JSON does not parse: %s" % exc, file=sys.stderr)
        return 1

    model = out.get("model", "?")
    failures = []   # (quantity, point label, values, rotgen, sympy)
    structural = []

    def check_equal(what, got, want, source="the model file gives"):
        if got != want:
            structural.append("%s: rotgen reports %r, %s %r" % (what, got, source, want))

    check_equal("model", out.get("model"), doc.get("name"))
    check_equal("coordinates", out.get("coordinates"), list(COORDS))
    check_equal("parameters", out.get("parameters"), file_params)
    params = dict(out.get("parameters", {}))
    pnames = sorted(params)

    syms = SymbolTable()
    try:
        ref = Derivation(doc, params, syms, args.inject_error)
        P = set(pnames)
        q_, qd_, qdd_, p_ = set(COORDS), set(RATES), set(ACCELS), set(MOMENTA)

        def rg(path, allowed):
            node = out
            for key in path:
                node = node[key]
            return syms.parse(node, allowed, "rotgen " + label_of(path))

        rot = {}
        rot["kinetic"] = rg(["kinetic"], P | q_ | qd_)
        for i in range(3):  # omega = J(q) q_dot: J, compared at random q_dot
            rot["omega[%d]" % i] = rg(["omega", i], q_ | qd_)
        rot["potential"] = rg(["potential"], P | q_)
        rot["lagrangian"] = rg(["lagrangian"], P | q_ | qd_)
        rot["energy"] = rg(["energy"], P | q_ | qd_)
        for i in range(3):
            rot["momenta[%d]" % i] = rg(["momenta", i], P | q_ | qd_)
            for j in range(3):
                rot["mass_matrix[%d][%d]" % (i, j)] = rg(["mass_matrix", i, j], P | q_)
            rot["euler_lagrange[%d]" % i] = rg(["euler_lagrange", i],
                                               P | q_ | qd_ | qdd_ | {"t"})
            rot["hamilton_equations.qdot[%d]" % i] = rg(["hamilton_equations", "qdot", i],
                                                        P | q_ | p_)
            rot["hamilton_equations.pdot[%d]" % i] = rg(["hamilton_equations", "pdot", i],
                                                        P | q_ | p_ | {"t"})
        rot["hamiltonian"] = rg(["hamiltonian"], P | q_ | p_)
    except ModelError as exc:
        print("sympy_crosscheck: error: %s" % exc, file=sys.stderr)
        return 2
    except AssertionError as exc:
        print("sympy_crosscheck: error: %s" % exc, file=sys.stderr)
        return 1
    except (KeyError, IndexError, TypeError) as exc:
        print("sympy_crosscheck: error: rotgen's JSON lacks %s" % exc, file=sys.stderr)
        return 1

    # One argument order for every numerical function.
    names = list(COORDS + RATES + ACCELS + MOMENTA) + ["t"] + pnames
    arglist = [syms[n] for n in names]

    def numeric(e):
        return sp.lambdify(arglist, e, modules="mpmath")

    f_rot = {k: numeric(v) for k, v in rot.items()}
    f_T, f_V, f_L, f_E = (numeric(e) for e in (ref.T, ref.V, ref.L, ref.E))
    f_w = [numeric(e) for e in ref.omega]
    f_p = [numeric(e) for e in ref.p]
    f_M = numeric(ref.M)
    f_dM = [numeric(m) for m in ref.dM]
    f_dV = [numeric(e) for e in ref.dV]
    f_dLdq = [numeric(e) for e in ref.dLdq]
    f_Q = [numeric(e) for e in ref.Q]
    f_EL = [numeric(e) for e in ref.EL]

    rng = random.Random(args.seed)

    def u(a, b):
        return mpmath.mpf(repr(rng.uniform(a, b)))

    def random_parameters():
        return {n: (mpmath.mpf(repr(v)) * u(0.5, 1.5) if v != 0 else u(-0.5, 0.5))
                for n, v in params.items()}

    nonzero_dLdq = [False] * 3
    nonzero_Q = [False] * 3
    npoints = 0
    for kind in ("default", "random"):
        for k in range(args.points):
            pv = ({n: mpmath.mpf(repr(v)) for n, v in params.items()} if kind == "default"
                  else random_parameters())
            # the middle angle away from the singular set: sin beta = 0 (proper Euler), cos beta = 0
            # (Tait-Bryan)
            beta = (u(0.2, math.pi - 0.2) if AXES[0] == AXES[2]
                    else u(-math.pi / 2 + 0.2, math.pi / 2 - 0.2))
            qv = [u(0, 2 * math.pi), beta, u(0, 2 * math.pi)]
            qdv = [u(-3, 3) for _ in range(3)]
            qddv = [u(-5, 5) for _ in range(3)]
            pr = [u(-3, 3) for _ in range(3)]  # a random momentum, for the Hamiltonian side
            tv = u(0, 10)
            npoints += 1
            label = "point %d (%s parameters)" % (npoints, kind)

            def at(qdot, mom):
                vals = dict(zip(COORDS, qv))
                vals.update(zip(RATES, qdot))
                vals.update(zip(ACCELS, qddv))
                vals.update(zip(MOMENTA, mom))
                vals["t"] = tv
                vals.update(pv)
                return [vals[n] for n in names], vals

            def compare(quantity, args_, vals, want, shown):
                got = f_rot[quantity](*args_)
                if not agree(got, want):
                    failures.append((quantity, label,
                                     {n: vals[n] for n in shown + pnames}, got, want))

            # Lagrangian side at (q, q_dot, q_ddot, t)
            M_qd = mpmath.matrix(f_M(*at(qdv, pr)[0]))
            p_of_qd = [sum(M_qd[i, j] * qdv[j] for j in range(3)) for i in range(3)]
            a, vals = at(qdv, p_of_qd)
            lag_vars = list(COORDS + RATES)
            compare("kinetic", a, vals, f_T(*a), lag_vars)
            for i in range(3):
                compare("omega[%d]" % i, a, vals, f_w[i](*a), lag_vars)
            compare("potential", a, vals, f_V(*a), list(COORDS))
            compare("lagrangian", a, vals, f_L(*a), lag_vars)
            compare("energy", a, vals, f_E(*a), lag_vars)
            for i in range(3):
                compare("momenta[%d]" % i, a, vals, f_p[i](*a), lag_vars)
                for j in range(3):
                    compare("mass_matrix[%d][%d]" % (i, j), a, vals, M_qd[i, j], list(COORDS))
                compare("euler_lagrange[%d]" % i, a, vals, f_EL[i](*a),
                        list(COORDS + RATES + ACCELS) + ["t"])
                nonzero_dLdq[i] |= not agree(f_dLdq[i](*a), 0)
                nonzero_Q[i] |= not agree(f_Q[i](*a), 0)
            # H at p = M q_dot is T + V; Hamilton's q_dot gives back the q_dot that built p.
            ham_vars = list(COORDS + MOMENTA)
            compare("hamiltonian", a, vals, f_E(*a), ham_vars)
            for i in range(3):
                compare("hamilton_equations.qdot[%d]" % i, a, vals, qdv[i], ham_vars)

            # Hamiltonian side at a random momentum: q_dot = M^{-1} p,
            # H = 1/2 p.q_dot + V, -dH/dq_k = 1/2 q_dot^T dM/dq_k q_dot - dV/dq_k, p_dot = -dH/dq + Q
            qd_of_p = list(mpmath.lu_solve(M_qd, mpmath.matrix(pr)))
            a, vals = at(qd_of_p, pr)
            compare("hamiltonian", a, vals,
                    sum(pr[i] * qd_of_p[i] for i in range(3)) / 2 + f_V(*a), ham_vars)
            for k in range(3):
                compare("hamilton_equations.qdot[%d]" % k, a, vals, qd_of_p[k], ham_vars)
                dM = mpmath.matrix(f_dM[k](*a))
                minus_dHdq = sum(qd_of_p[i] * dM[i, j] * qd_of_p[j]
                                 for i in range(3) for j in range(3)) / 2 - f_dV[k](*a)
                compare("hamilton_equations.pdot[%d]" % k, a, vals, minus_dHdq + f_Q[k](*a),
                        ham_vars + ["t"])

    cyclic = [COORDS[i] for i in range(3) if not nonzero_dLdq[i] and not nonzero_Q[i]]
    check_equal("cyclic", out.get("cyclic"), cyclic, "SymPy finds dL/dq = Q = 0 for")

    ncompared = len(rot) * 2 * npoints
    if not failures and not structural:
        print("sympy_crosscheck %s: OK: %d quantities agree at %d points (%d at defaults, %d at "
              "random parameters), relative tolerance %g; cyclic %s"
              % (model, len(rot), npoints, args.points, args.points, RTOL, cyclic))
        return 0

    for msg in structural:
        print("MISMATCH %s: %s" % (model, msg))
    for quantity, label, vals, got, want in failures[:6]:
        diff = abs(got - want)
        rel = diff / max(abs(got), abs(want)) if max(abs(got), abs(want)) else diff
        print("MISMATCH %s: %s at %s" % (model, quantity, label))
        print("  at      " + ", ".join("%s=%s" % (n, fmt(v)) for n, v in vals.items()))
        print("  rotgen  = %s\n  sympy   = %s\n  |diff|  = %s (relative %s)"
              % (fmt(got), fmt(want), fmt(diff), mpmath.nstr(rel, 3)))
    counts = {}
    for f in failures:
        counts[f[0]] = counts.get(f[0], 0) + 1
    if counts:
        print("sympy_crosscheck %s: FAILED: %d of about %d comparisons disagree: %s"
              % (model, len(failures), ncompared,
                 ", ".join("%s (%d)" % kv for kv in sorted(counts.items()))))
    else:
        print("sympy_crosscheck %s: FAILED" % model)
    return 1


def label_of(path):
    s = str(path[0])
    for key in path[1:]:
        s += "[%d]" % key if isinstance(key, int) else "." + key
    return s


if __name__ == "__main__":
    sys.exit(main())
