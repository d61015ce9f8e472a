#!/usr/bin/env python3
"""The largest Lyapunov exponent of a heavy top by renormalised tangent vectors (Benettin's method).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/lyapunov.py [FIGURE.png] [T]

Run from the repository root. Two tops in the body form (quaternion and body omega), started alike:
the shipped full-tensor top (models/full_tensor_top.yaml: no symmetry, its centre of mass off every
axis; not integrable) and the symmetric Lagrange top (models/heavy_top.yaml: integrable, so its
exponent tends to 0). Every TAU time units the run's state-transition matrix Phi (the scene's
`sensitivities: {keys: all_initial}`, r.stm) carries a tangent vector v; ln |Phi v| is summed and
v renormalised, and the next interval starts from the last state (lambda(t) = sum / t). Prints both
exponents at T (default 1000) and writes the figure lambda(t) (default lyapunov.png;
docs/lyapunov.png is this figure at T = 10000).

The samples record the quaternion with q0 >= 0 (q and -q are one attitude); the run's own state
turns continuously, so where the recorded q changes sign between two samples the state's
quaternion is -q: the tangent vector's quaternion part follows the state's sign.
"""

import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt

import rotgen

TAU = 5.0
Q = ["q0", "q1", "q2", "q3"]
W = ["omega1", "omega2", "omega3"]


START = {"phi": 0.3, "theta": 1.2, "psi": 0.1, "omega1": 0.5, "omega2": -0.3, "omega3": 0.5}


def scene_of(model, initial):
    return rotgen.Scene({
        "model": f"models/{model}.yaml",
        "form": "body",
        "initial": initial,
        "time": {"start": 0, "end": TAU, "samples": 501},
        "integrator": {"method": "dop853", "rtol": 1e-11, "atol": 1e-13},
        "record": Q + W,
        "sensitivities": {"keys": "all_initial"},
    })


def sign_of_state(q):
    """+1 or -1: the state's quaternion at the last sample is sign * the recorded one (the record
    flips q to -q where q0 crosses 0; the state does not)."""
    jumps = np.linalg.norm(np.diff(q, axis=0), axis=1) > 1.0
    return -1.0 if np.count_nonzero(jumps) % 2 else 1.0


def exponent(model, t_end):
    scene = scene_of(model, START)
    v = np.ones(7) / np.sqrt(7.0)
    total, times, lambdas = 0.0, [], []
    for k in range(int(round(t_end / TAU))):
        r = rotgen.simulate(scene)
        v = r.stm[-1] @ v  # y = (qw, qx, qy, qz, omega1, omega2, omega3)
        growth = np.linalg.norm(v)
        total += np.log(growth)
        v /= growth
        q = np.column_stack([r[c] for c in Q])
        v[:4] *= sign_of_state(q)  # the next run starts from the recorded q (q0 >= 0)
        times.append((k + 1) * TAU)
        lambdas.append(total / times[-1])
        last = {c: float(r[c][-1]) for c in Q + W}
        scene = scene_of(model, last)
    return np.array(times), np.array(lambdas)


def main():
    figure = sys.argv[1] if len(sys.argv) > 1 else "lyapunov.png"
    t_end = float(sys.argv[2]) if len(sys.argv) > 2 else 1000.0
    curves = {name: exponent(model, t_end) for name, model in
              [("full-tensor top (not integrable)", "full_tensor_top"),
               ("Lagrange top (integrable)", "heavy_top")]}
    fig, ax = plt.subplots(figsize=(7, 3.5))
    for name, (t, lam) in curves.items():
        ax.semilogx(t, lam, label=name)
        print(f"{name}: lambda({t[-1]:g}) = {lam[-1]:.4g}")
    chaotic, regular = (curves[n][1][-1] for n in curves)
    print(f"ratio regular / chaotic = {regular / chaotic:.3g}")
    ax.axhline(0, color="grey", lw=0.5)
    ax.set(xlabel="t", ylabel="λ(t) = (1/t) Σ ln |Φ v|",
           title="largest Lyapunov exponent, renormalised tangent vectors every 5")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(figure, dpi=110)
    print(f"wrote {figure}")


if __name__ == "__main__":
    main()
