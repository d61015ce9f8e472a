"""rotgen fit in the lagrangian form, before and after its Jacobian came from the sensitivities
there too (d(q0..q3)/d(key) and the angles' derivatives are now given in every form; before, the
Euler-angle forms took central differences of whole runs, 2k more runs per Jacobian).

Two problems: tumbling_lagrangian.yaml (docs/fitting.md's worked example, examples/fit/gyro.csv, in
the lagrangian form) and top_lagrangian.yaml (the full-tensor top's six inertia entries from a
simulated gyro and star tracker: q0..q3 measured). Each with `rotgen fit` (wall time: the median of
9 whole commands, before and after in turn), with the rotgen built before the change when it is given. Then where the time
of a run with sensitivities goes, for the top: `rotgen sweep` of 1 and of 201 members (best of 5),
with and without the six keys' sensitivities: the preparation (about the 1-member sweep) and the
cost of one more run ((201 - 1) members / 200).

    /usr/bin/python3 bench/fit/lagrangian.py build/rotgen [BEFORE] > bench/results/fit_lagrangian.md
    (BEFORE_LABEL=TEXT: what BEFORE is, for the header; bench/results/README.md has the runs)
"""

import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np
import pandas as pd

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..", "..")
exe = sys.argv[1] if len(sys.argv) > 1 else "rotgen"
before = sys.argv[2] if len(sys.argv) > 2 else None
# what BEFORE is, for the file's header
BEFORE_LABEL = os.environ.get("BEFORE_LABEL", "rotgen at main 3d54143, whose fit took central "
                              "differences in the Euler-angle forms")
inertia = ["parameters." + n for n in ("Ixx", "Iyy", "Izz", "Ixy", "Ixz", "Iyz")]


REPEATS = 9


def measured_fits(programs, scene, data, free, sigma):
    """For each program: the median wall time of REPEATS whole commands, the programs run in turn
    (so that the machine's load falls on each alike); evaluations, Jacobians, runs, source, chi2."""
    walls, outs = [[] for _ in programs], [None] * len(programs)
    for _ in range(REPEATS):
        for i, program in enumerate(programs):
            t0 = time.perf_counter()
            outs[i] = subprocess.run([program, "fit", scene, "--data", data, "--free",
                                      ",".join(free), "--sigma", sigma], check=True,
                                     capture_output=True, text=True).stdout
            walls[i].append(time.perf_counter() - t0)
    rows = []
    for wall, out in zip(walls, outs):
        m = re.search(r"(\d+) evaluations, (\d+) Jacobians (from the sensitivities|by central "
                      r"differences)? ?\((\d+) runs\)", out)
        source = m.group(3) or "central differences"
        chi2 = float(re.search(r"chi2 (\S+)", out).group(1))
        rows.append((sorted(wall)[len(wall) // 2], int(m.group(1)), int(m.group(2)),
                     int(m.group(4)), source, chi2))
    return rows


def top_data(exe, path):
    """The tilted top's truth (body form) sampled on a fine grid, 200 of its rows with gyro
    (1e-3 rad/s) and star-tracker (1e-4 rad) noise: seed 2026."""
    truth = os.path.join(os.path.dirname(path), "top_truth.yaml")
    with open(os.path.join(here, "top_lagrangian.yaml")) as f:
        text = f.read()
    text = re.sub(r"parameters: .*\n", "", text).replace("form: lagrangian", "form: body")
    text = text.replace("../../models/", os.path.join(root, "models") + "/")
    text = text.replace("samples: 101", "samples: 3001")
    text = text.replace("record: [omega1, omega2, omega3]",
                        "record: [omega1, omega2, omega3, q0, q1, q2, q3]")
    with open(truth, "w") as f:
        f.write(text)
    try:
        csv = os.path.join(os.path.dirname(path), "top_truth.csv")
        subprocess.run([exe, "simulate", truth, "-o", csv, "-q"], check=True)
        d = pd.read_csv(csv, comment="#")
        os.remove(csv)
    finally:
        os.remove(truth)
    rng = np.random.default_rng(2026)
    d = d.iloc[np.sort(rng.choice(len(d), 200, replace=False))].copy()
    for c in ("omega1", "omega2", "omega3"):
        d[c] += 1e-3 * rng.standard_normal(len(d))
    for i in range(len(d)):  # q (x) exp(e/2), e a small body-axis rotation vector
        q = d.iloc[i][["q0", "q1", "q2", "q3"]].to_numpy()
        e = 1e-4 * rng.standard_normal(3)
        a = np.linalg.norm(e)
        r = np.concatenate([[np.cos(a / 2)], np.sin(a / 2) * e / a])
        w0, v0, w1, v1 = q[0], q[1:], r[0], r[1:]
        m = np.concatenate([[w0 * w1 - v0 @ v1], w0 * v1 + w1 * v0 + np.cross(v0, v1)])
        d.iloc[i, [d.columns.get_loc(c) for c in ("q0", "q1", "q2", "q3")]] = m
    d.to_csv(path, index=False, float_format="%.17g")




def sweep_seconds(scene_text, members):
    """Best of 5 of `rotgen sweep` of `members` members (omega3 from 8 to 8.1), one thread."""
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "scene.yaml")
        with open(scene, "w") as f:
            f.write(scene_text)
        best = float("inf")
        for _ in range(5):
            t0 = time.perf_counter()
            subprocess.run([exe, "sweep", scene, "-o", os.path.join(tmp, "out"), "-j", "1",
                            "--vary", f"initial.omega3=8:8.1:{members}"], check=True,
                           capture_output=True)
            best = min(best, time.perf_counter() - t0)
    return best


with tempfile.TemporaryDirectory() as tmp:
    top_csv = os.path.join(tmp, "top_data.csv")
    top_data(exe, top_csv)
    sigma = 2e-3
    problems = [
        ("tumbling body (5 keys, gyro)", os.path.join(here, "tumbling_lagrangian.yaml"),
         os.path.join(root, "examples", "fit", "gyro.csv"),
         ["parameters.I1", "parameters.I2", "initial.omega1", "initial.omega2", "initial.omega3"],
         f"omega1={sigma},omega2={sigma},omega3={sigma}"),
        ("full-tensor top (6 keys, gyro and star tracker)",
         os.path.join(here, "top_lagrangian.yaml"), top_csv, inertia,
         "omega1=1e-3,omega2=1e-3,omega3=1e-3,q=1e-4"),
    ]
    print("# rotgen fit in the lagrangian form, before and after the sensitivities' Jacobian")
    print()
    print("Made by `/usr/bin/python3 bench/fit/lagrangian.py build/rotgen BEFORE` (BEFORE: " + BEFORE_LABEL + ")")
    print("on the development machine (2 cores, otherwise idle), " + time.strftime("%Y-%m-%d") + ".")
    print()
    print("| problem | rotgen | Jacobian | wall time (s) | evaluations | Jacobians | runs | chi2 |")
    print("|---|---|---|---|---|---|---|---|")
    runs_of = [(label, program) for label, program in (("before", before), ("after", exe)) if program]
    for name, scene_file, data_file, free, sig in problems:
        rows = measured_fits([p for _, p in runs_of], scene_file, data_file, free, sig)
        for (label, _), (wall, evals, jacs, runs, source, chi2) in zip(runs_of, rows):
            print(f"| {name} | {label} | {source} | {wall:.3f} | {evals} | {jacs} | {runs} | "
                  f"{chi2:.6g} |")

with open(os.path.join(here, "top_lagrangian.yaml")) as f:
    top = f.read().replace("../../models/", os.path.join(root, "models") + "/")
print()
print("Where a run's time goes (the top, `rotgen sweep`, best of 5):")
print()
print("| sensitivities | 1 member (s) | 201 members (s) | one more run (ms) |")
print("|---|---|---|---|")
for label, text in (("none", top), ("6 keys", top + f"sensitivities: [{', '.join(inertia)}]\n")):
    one, many = sweep_seconds(text, 1), sweep_seconds(text, 201)
    print(f"| {label} | {one:.3f} | {many:.3f} | {1000 * (many - one) / 200:.2f} |")
