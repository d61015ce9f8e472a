#!/usr/bin/env python3
"""rotgen sweep --trajectories of a scene with sensitivities, read back with h5py: the dataset's
columns are t, the recorded columns, then every d(<column>)/d(<key>) in record order then key
order, and each member's samples of them are those of `rotgen simulate` run on its own scene (an
independent run, read through Python's csv), and the last sample is summary.csv's final.d(...).

    sweep_trajectories_sensitivities.py --rotgen BUILD/rotgen --model MODELS/heavy_top.yaml
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

import h5py

COLUMNS = ["t", "theta", "energy", "d(theta)/d(initial.theta)", "d(theta)/d(parameters.h)",
           "d(energy)/d(initial.theta)", "d(energy)/d(parameters.h)"]


def scene_text(model, h, sweep):
    text = (f"model: {model}\nform: lagrangian\nparameters: {{h: {h}}}\n"
            "initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0.3, theta_dot: 0.1, psi_dot: 5}\n"
            "time: {end: 1, samples: 11}\n"
            "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}\n"
            "record: [theta, energy]\nswitch_chart: false\n"
            "sensitivities: [initial.theta, parameters.h]\n")
    if sweep:
        text += "sweep:\n  mode: grid\n  vary:\n    parameters.h: {values: [0.1, 0.2]}\n"
    return text


def simulated(rotgen, model, h, tmp):
    """The rows of `rotgen simulate` of the scene with this h: {column: [values]}."""
    scene = os.path.join(tmp, f"member_{h}.yaml")
    with open(scene, "w") as f:
        f.write(scene_text(model, h, False))
    out = os.path.join(tmp, f"member_{h}.csv")
    r = subprocess.run([rotgen, "simulate", scene, "-o", out], capture_output=True, text=True)
    assert r.returncode == 0, (r.returncode, r.stderr)
    with open(out, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return {c: [float(row[c]) for row in rows] for c in rows[0]}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rotgen", required=True)
    ap.add_argument("--model", required=True)
    a = ap.parse_args()
    a.model = os.path.abspath(a.model)
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "scene.yaml")
        with open(scene, "w") as f:
            f.write(scene_text(a.model, 0.1, True))
        out = os.path.join(tmp, "out")
        r = subprocess.run([a.rotgen, "sweep", scene, "-o", out, "--trajectories", "-q"],
                           capture_output=True, text=True)
        assert r.returncode == 0, (r.returncode, r.stderr)
        with open(os.path.join(out, "summary.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        d = h5py.File(os.path.join(out, "trajectories.h5"), "r")["trajectories"]
        assert [str(c) for c in d.attrs["columns"]] == COLUMNS, d.attrs["columns"]
        assert d.shape == (2, 11, len(COLUMNS)), d.shape
        for m, h in enumerate((0.1, 0.2)):
            own = simulated(a.rotgen, a.model, h, tmp)
            for c, name in enumerate(COLUMNS):
                assert len(own[name]) == 11, (name, len(own[name]))
                for s in range(11):  # observed equal: the same run, its numbers printed exactly
                    assert d[m, s, c] == own[name][s], (m, name, s, d[m, s, c], own[name][s])
                if name.startswith("d("):
                    assert float(rows[m]["final." + name]) == d[m, 10, c], (m, name)
            assert any(abs(x) > 1e-3 for x in d[m, :, 4].flat)  # d(theta)/d(h) moves
    print("trajectories.h5: the d(...) columns of each member agree with its own simulate run")
    return 0


if __name__ == "__main__":
    sys.exit(main())
