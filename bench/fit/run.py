"""rotgen fit against SciPy's least_squares on the same problem: examples/fit/tumbling.yaml's
five keys (I1, I2 and the initial spin) fitted to examples/fit/gyro.csv from the same start.

rotgen fit: Levenberg-Marquardt (Eigen), its Jacobian the sensitivities integrated with the run.
SciPy: least_squares(method="lm", x_scale="jac") (MINPACK), its Jacobian by finite differences of runs, each run
through the Python module (rotgen.simulate of the scene with the keys changed: the scene read and
prepared anew, the kernels from rotgen's cache), sampled on the 2001-point grid the data's times
were drawn from.

    PYTHONPATH=build/python /usr/bin/python3 bench/fit/run.py build/rotgen > bench/fit/results.md
"""

import os
import re
import subprocess
import sys
import time

import numpy as np
import pandas as pd
import scipy.optimize

import rotgen

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..", "..")
exe = sys.argv[1] if len(sys.argv) > 1 else "rotgen"
scene = os.path.join(root, "examples", "fit", "tumbling.yaml")
data = os.path.join(root, "examples", "fit", "gyro.csv")
keys = ["parameters.I1", "parameters.I2", "initial.omega1", "initial.omega2", "initial.omega3"]
sigma = 2e-3

# rotgen fit (the command, as a user runs it; the best of 3)
times = []
for _ in range(3):
    t0 = time.perf_counter()
    out = subprocess.run([exe, "fit", scene, "--data", data, "--free", ",".join(keys),
                          "--sigma", f"omega1={sigma},omega2={sigma},omega3={sigma}"],
                         check=True, capture_output=True, text=True).stdout
    times.append(time.perf_counter() - t0)
chi2 = float(re.search(r"chi2 (\S+)", out).group(1))
its, evals, jacs = map(int, re.search(r"(\d+) iterations, (\d+) evaluations, (\d+) Jacobians",
                                      out).groups())
estimates = {m.group(1): float(m.group(2))
             for m in re.finditer(r"^(\S+\.\S+)\s+(\S+)\s", out, re.M)}

# SciPy least_squares, the model through rotgen.simulate
d = pd.read_csv(data)
start = rotgen.Scene(scene).with_({"time.samples": 2001})
rows = np.rint(d["t"].to_numpy() / 0.005).astype(int)
measured = d[["omega1", "omega2", "omega3"]].to_numpy()
mask = ~np.isnan(measured)
x0 = [1.3, 1.6, 0.35, 0.8, 0.25]


def residuals(x):
    try:  # an unphysical trial step: a large residual (as rotgen fit rejects it)
        s = start.with_({k: float(v) for k, v in zip(keys, x)})
    except rotgen.InputError:
        return np.full(int(mask.sum()), 1e10)
    run = rotgen.simulate(s)
    y = np.column_stack([run["omega1"], run["omega2"], run["omega3"]])[rows]
    return ((y - measured) / sigma)[mask]


t0 = time.perf_counter()
s = scipy.optimize.least_squares(residuals, x0, method="lm", x_scale="jac")
scipy_time = time.perf_counter() - t0

print("| solver | wall time (s) | iterations | residual evaluations | Jacobians | chi2 |")
print("|---|---|---|---|---|---|")
print(f"| rotgen fit (sensitivities) | {min(times):.3f} | {its} | {evals} | {jacs} | {chi2:.6g} |")
print(f"| SciPy least_squares lm (finite differences) | {scipy_time:.3f} | - | {s.nfev} | "
      f"{s.njev if s.njev is not None else '-'} | {float(np.sum(s.fun ** 2)):.6g} |")
print()
print(f"speed-up {scipy_time / min(times):.1f}x; estimates (rotgen, SciPy):")
for k, v in zip(keys, s.x):
    print(f"- {k}: {estimates.get(k, float('nan')):.9g}, {v:.9g}")
