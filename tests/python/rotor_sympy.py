#!/usr/bin/python3
"""Independent SymPy check of a linear rotor's emitted equations (`rotgen emit`, form rotor).

    /usr/bin/python3 tests/python/rotor_sympy.py --rotgen build/rotgen --model models/dumbbell.yaml

The model may be a model file or a scene file with an inline `model:` mapping. The script emits
the rotor form's header, compiles a small driver with g++ -std=c++17 -Wall -Wextra -Wpedantic
-Werror (so the header is also checked to be warning-free) that prints rhs, energy and momenta at
random states with the model's default parameters, and compares them with a SymPy derivation
that never reads rotgen's output:

  * the line's direction in space is the third row of A = Az(psi) Ax(theta) Az(phi) (5.25, 5.8,
    5.9), computed here from the rotation matrices (it must not depend on psi);
  * a body of point masses (`body: parts:`, all on one line through the pivot): each mass at
    s_k n in space, s_k its signed distance from the pivot along the line, so
    T = sum 1/2 m_k s_k^2 |n_dot|^2 and the gravity shorthand gives V = sum m_k g s_k n_z (the
    centre of mass's side of the pivot counted positive; s_k from the parts' coordinates);
    a body given by `inertia: [0, J, J]`: T = 1/2 J |n_dot|^2 and V the `potential:` field;
  * Lagrange's equations by differentiating functions phi(t), theta(t) in time, solved for the
    accelerations; p = dL/dq_dot; E = T + V.

Values agree within 1e-11 relative (or 1e-13 absolute near zero). Exit 1 on a mismatch, printed
with the quantity, the state and both values.
"""

import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile

import sympy as sp
import yaml

RTOL, ATOL = 1e-11, 1e-13


def az(a):
    return sp.Matrix([[sp.cos(a), sp.sin(a), 0], [-sp.sin(a), sp.cos(a), 0], [0, 0, 1]])


def ax(a):
    return sp.Matrix([[1, 0, 0], [0, sp.cos(a), sp.sin(a)], [0, -sp.sin(a), sp.cos(a)]])


def load_model(path):
    with open(path) as f:
        doc = yaml.safe_load(f)
    return doc["model"] if "model" in doc else doc


def defaults(model):
    values = {}
    for name, p in (model.get("parameters") or {}).items():
        values[sp.Symbol(name, real=True)] = p["value"] if isinstance(p, dict) else p
    return values


def parse(text, params):
    names = {str(s): s for s in params}
    names.update({"pi": sp.pi, "sin": sp.sin, "cos": sp.cos, "sqrt": sp.sqrt})
    return sp.sympify(str(text), locals=names)


def energies(model, params, angles, n, nd):
    """T and V of the rotor whose line points along n (functions of t, the angles phi(t),
    theta(t))."""
    if "body" not in model:
        J = sum(parse(v, params) for v in model["inertia"]) / 2
        phi, theta = sp.Symbol("phi", real=True), sp.Symbol("theta", real=True)
        V = parse(model.get("potential", 0), {**params, phi: 0, theta: 0})
        return J * nd.dot(nd) / 2, V.subs({phi: angles[0], theta: angles[1]})
    body = model["body"]
    pivot = sp.Matrix([parse(c, params) for c in body.get("pivot", [0, 0, 0])])
    masses, positions = [], []
    for part in body["parts"]:
        point = part["point"]
        masses.append(parse(point["mass"], params))
        positions.append(sp.Matrix([parse(c, params) for c in point["at"]]) - pivot)
    M = sum(masses)
    com = sum((m * r for m, r in zip(masses, positions)), sp.zeros(3, 1)) / M
    # the line's unit vector: towards the centre of mass (any direction of the line if it is 0)
    at = {**defaults(model)}
    ref = com if float(com.subs(at).norm()) > 1e-12 else next(
        r for r in positions if float(r.subs(at).norm()) > 1e-12)
    u = ref / sp.sqrt(ref.dot(ref))
    s = [r.dot(u) for r in positions]
    T = sum(m * sk ** 2 for m, sk in zip(masses, s)) * nd.dot(nd) / 2
    V = 0
    if "gravity" in model:
        g = parse(model["gravity"]["g"], params)
        V = sum(m * g * sk for m, sk in zip(masses, s)) * n[2]
    return T, V


def derive(model, flip_potential=False):
    params = defaults(model)
    t = sp.Symbol("t", real=True)
    phi_t, theta_t, psi = sp.Function("phi")(t), sp.Function("theta")(t), sp.Symbol("psi")
    A = az(psi) * ax(theta_t) * az(phi_t)
    n = A[2, :].T
    assert all(sp.simplify(c.diff(psi)) == 0 for c in n), "the line's direction depends on psi"
    nd = n.diff(t)
    T, V = energies(model, params, (phi_t, theta_t), n, nd)
    V = -V if flip_potential else V
    L = T - V
    q, qd = [phi_t, theta_t], [phi_t.diff(t), theta_t.diff(t)]
    qdd = [phi_t.diff(t, 2), theta_t.diff(t, 2)]
    eqs = [sp.diff(L.diff(qd[i]), t) - L.diff(q[i]) for i in range(2)]
    acc = sp.solve(eqs, qdd, dict=True)[0]
    plain = sp.symbols("phi theta phi_dot theta_dot", real=True)
    to_plain = {qd[0]: plain[2], qd[1]: plain[3]}
    to_plain2 = {phi_t: plain[0], theta_t: plain[1]}

    plain_dd = sp.symbols("phi_ddot theta_ddot", real=True)

    def flat(e):
        e = sp.sympify(e).subs({qdd[0]: plain_dd[0], qdd[1]: plain_dd[1]})
        return e.subs(to_plain).subs(to_plain2).subs(params)

    return plain + plain_dd, {
        "phi_ddot": flat(acc[qdd[0]]),
        "theta_ddot": flat(acc[qdd[1]]),
        "energy": flat(T + V),
        "p_phi": flat(L.diff(qd[0])),
        "p_theta": flat(L.diff(qd[1])),
        # for `inspect` (--inspect): T, V, L, Lagrange's equations d/dt dL/dq_dot - dL/dq (= 0),
        # and dL/dq, which is p_dot along a motion
        "kinetic": flat(T),
        "potential": flat(V),
        "lagrangian": flat(L),
        "el_phi": flat(eqs[0]),
        "el_theta": flat(eqs[1]),
        "dLdq_phi": flat(L.diff(q[0])),
        "dLdq_theta": flat(L.diff(q[1])),
    }


DRIVER = """#include "{unit}.hpp"
#include <cstdio>
int main() {{
    namespace m = rotgen::models::{unit};
    m::params<double> p;
    double y[4];
    while (std::scanf("%lf %lf %lf %lf", &y[0], &y[1], &y[2], &y[3]) == 4) {{
        double d[4], mom[2];
        m::rhs(0.0, y, d, p);
        m::momenta(y, mom, p);
        std::printf("%.17g %.17g %.17g %.17g %.17g\\n", d[2], d[3], m::energy(y, p), mom[0],
                    mom[1]);
    }}
}}
"""


def generated(rotgen, model_path, model, points, work):
    if "model" in yaml.safe_load(open(model_path)):
        model_path = os.path.join(work, "model.yaml")
        with open(model_path, "w") as f:
            yaml.safe_dump(model, f)
    subprocess.run([rotgen, "emit", model_path, "-o", work], check=True, stdout=subprocess.DEVNULL)
    unit = model["name"] + "_rotor"
    with open(os.path.join(work, "driver.cpp"), "w") as f:
        f.write(DRIVER.format(unit=unit))
    exe = os.path.join(work, "driver")
    subprocess.run(["g++", "-std=c++17", "-O1", "-Wall", "-Wextra", "-Wpedantic", "-Werror",
                    "-I", work, os.path.join(work, "driver.cpp"), "-o", exe], check=True)
    text = "\n".join(" ".join(repr(v) for v in y) for y in points)
    out = subprocess.run([exe], input=text, capture_output=True, text=True, check=True).stdout
    return [[float(v) for v in line.split()] for line in out.splitlines()]


def inspected(rotgen, model_path, extra):
    """`rotgen inspect MODEL --format json` (with `extra` options) as a dict of SymPy
    expressions in phi, theta, their rates and accelerations, p_phi, p_theta and the
    parameters (at their defaults)."""
    out = subprocess.run([rotgen, "inspect", model_path, "--format", "json"] + extra,
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out)


def check_inspect(rotgen, model_path, model, exprs, points, extra):
    """Compare inspect's T, V, L, momenta, Euler-Lagrange equations, H, Hamilton's equations and
    energy with the SymPy derivation at `points` (phi, theta, phi_dot, theta_dot, and the
    accelerations SymPy's Lagrange equations give there)."""
    doc = inspected(rotgen, model_path, extra)
    params = defaults(model)
    names = {str(k): k for k in params}
    syms = sp.symbols("phi theta phi_dot theta_dot phi_ddot theta_ddot p_phi p_theta", real=True)
    names.update({str(x): x for x in syms})
    names.update({"pi": sp.pi})

    def read(text):
        return sp.sympify(text.replace("^", "**"), locals=names).subs(params)

    assert doc["coordinates"] == ["phi", "theta"], doc["coordinates"]
    assert len(doc["momenta"]) == 2 and len(doc["mass_matrix"]) == 2
    if extra:
        assert doc["inertia"]["class"] == "rotor", doc["inertia"]["class"]
    phi, theta, phid, thetad, phidd, thetadd, pphi, ptheta = syms
    bad = 0
    for y in points:
        at = dict(zip(syms[:4], y))
        acc = {phidd: exprs["phi_ddot"].subs(at), thetadd: exprs["theta_ddot"].subs(at)}
        at_dd = {**at, **acc}
        p = [exprs["p_phi"].subs(at), exprs["p_theta"].subs(at)]
        at_p = {phi: y[0], theta: y[1], pphi: p[0], ptheta: p[1]}
        pairs = [
            ("kinetic", read(doc["kinetic"]).subs(at), exprs["kinetic"].subs(at)),
            ("potential", read(doc["potential"]).subs(at), exprs["potential"].subs(at)),
            ("lagrangian", read(doc["lagrangian"]).subs(at), exprs["lagrangian"].subs(at)),
            ("energy", read(doc["energy"]).subs(at), exprs["energy"].subs(at)),
            ("p_phi", read(doc["momenta"][0]).subs(at), p[0]),
            ("p_theta", read(doc["momenta"][1]).subs(at), p[1]),
            # Lagrange's equations, each = 0: equal at any accelerations (here y's and 0.7 more)
            ("el_phi", read(doc["euler_lagrange"][0]).subs(at_dd), 0),
            ("el_theta", read(doc["euler_lagrange"][1]).subs(at_dd), 0),
            ("el_phi off", read(doc["euler_lagrange"][0]).subs({**at, phidd: acc[phidd] + 0.7,
                                                                thetadd: acc[thetadd]}),
             exprs["el_phi"].subs({**at, phidd: acc[phidd] + 0.7, thetadd: acc[thetadd]})),
            ("hamiltonian", read(doc["hamiltonian"]).subs(at_p), exprs["energy"].subs(at)),
            ("phi_dot", read(doc["hamilton_equations"]["qdot"][0]).subs(at_p), y[2]),
            ("theta_dot", read(doc["hamilton_equations"]["qdot"][1]).subs(at_p), y[3]),
            ("p_phi_dot", read(doc["hamilton_equations"]["pdot"][0]).subs(at_p),
             exprs["dLdq_phi"].subs(at)),
            ("p_theta_dot", read(doc["hamilton_equations"]["pdot"][1]).subs(at_p),
             exprs["dLdq_theta"].subs(at)),
        ]
        for name, got, want in pairs:
            got, want = float(sp.N(got, 30)), float(sp.N(want, 30))
            if abs(got - want) > max(ATOL, RTOL * max(abs(got), abs(want))):
                bad += 1
                print("MISMATCH %s: inspect %s at %s: rotgen %r, sympy %r" % (
                    model["name"], name, y, got, want))
    cyclic = [c for c in doc["cyclic"]]
    want_cyclic = ["phi"] if sp.simplify(exprs["dLdq_phi"]) == 0 else []
    if cyclic != want_cyclic:
        bad += 1
        print("MISMATCH %s: cyclic %s, sympy %s" % (model["name"], cyclic, want_cyclic))
    return bad, len(points) * 14 + 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rotgen", required=True)
    ap.add_argument("--model", required=True)
    ap.add_argument("--points", type=int, default=8)
    ap.add_argument("--inject-error", choices=["potential-sign"],
                    help="derive V with the wrong sign on the SymPy side (the check must fail)")
    ap.add_argument("--inspect", action="store_true",
                    help="check `rotgen inspect --format json` (and with --inertia) instead of "
                         "the emitted header")
    args = ap.parse_args()
    model = load_model(args.model)
    plain, exprs = derive(model, args.inject_error == "potential-sign")
    rng = random.Random(14)
    points = [[rng.uniform(-3, 3), rng.uniform(0.2, math.pi - 0.2), rng.uniform(-2, 2),
               rng.uniform(-2, 2)] for _ in range(args.points)]
    if args.inspect:
        bad, checked = 0, 0
        for extra in ([], ["--inertia"]):
            b, c = check_inspect(args.rotgen, args.model, model, exprs, points, extra)
            bad, checked = bad + b, checked + c
        if bad:
            print("FAILED: %d of %d values" % (bad, checked))
            return 1
        print("rotor_sympy --inspect %s: %d values agree" % (model["name"], checked))
        return 0
    with tempfile.TemporaryDirectory() as work:
        got = generated(args.rotgen, args.model, model, points, work)
    names = ["phi_ddot", "theta_ddot", "energy", "p_phi", "p_theta"]
    bad = 0
    for y, row in zip(points, got):
        at = dict(zip(plain[:4], y))
        for name, value in zip(names, row):
            want = float(exprs[name].subs(at).evalf(30))
            if abs(value - want) > max(ATOL, RTOL * max(abs(value), abs(want))):
                bad += 1
                print("MISMATCH %s: %s at %s: rotgen %r, sympy %r" % (model["name"], name, y,
                                                                    value, want))
    checked = len(points) * len(names)
    if bad or len(got) != len(points):
        print("FAILED: %d of %d values" % (bad, checked))
        return 1
    print("rotor_sympy %s: %d values agree" % (model["name"], checked))
    return 0


if __name__ == "__main__":
    sys.exit(main())
