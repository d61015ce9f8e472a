"""The measurements of docs/fitting.md's example: the tumbling body of tumbling.yaml with its true
moments (I1 = 1, I2 = 2, I3 = 2.5) and initial spin (0.3, 1.0, 0.2), sampled by `rotgen simulate`
on a fine grid, 150 irregular samples kept (a gyro that drops readings), gyro noise 2e-3 rad/s, and
a few readings missing on one axis.

    /usr/bin/python3 examples/fit/make_data.py build/rotgen    # writes examples/fit/gyro.csv
"""

import os
import subprocess
import sys
import tempfile

import numpy as np
import pandas as pd

here = os.path.dirname(os.path.abspath(__file__))
rotgen = sys.argv[1] if len(sys.argv) > 1 else "rotgen"
truth = f"""model: {here}/../../models/free_asymmetric_top.yaml
parameters: {{I3: 2.5}}
form: body
initial: {{phi: 0, theta: 0.3, psi: 0, omega1: 0.3, omega2: 1.0, omega3: 0.2}}
time: {{start: 0, end: 10, samples: 2001}}
integrator: {{method: dop853, rtol: 1e-12, atol: 1e-14}}
record: [omega1, omega2, omega3]
"""
with tempfile.TemporaryDirectory() as tmp:
    scene = os.path.join(tmp, "truth.yaml")
    with open(scene, "w") as f:
        f.write(truth)
    subprocess.run([rotgen, "simulate", scene, "-o", os.path.join(tmp, "truth.csv"), "-q"],
                   check=True)
    d = pd.read_csv(os.path.join(tmp, "truth.csv"), comment="#")
rng = np.random.default_rng(2026)
d = d.iloc[np.sort(rng.choice(len(d), 150, replace=False))].copy()
for c in ("omega1", "omega2", "omega3"):
    d[c] += 2e-3 * rng.standard_normal(len(d))
d.loc[d.index[rng.choice(len(d), 6, replace=False)], "omega2"] = np.nan
d.to_csv(os.path.join(here, "gyro.csv"), index=False, na_rep="", float_format="%.9g")
