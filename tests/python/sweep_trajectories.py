#!/usr/bin/env python3
"""rotgen sweep --trajectories read back with h5py (Debian's python3-h5py): the dataset's shape
[member, sample, column], its attributes (columns, varied keys, the scene's text), the varied
values, and every member's last sample against the final values summary.csv gives for it (a
second, independent reader: Python's csv and float parsing). A failed member's samples past the
point it reached are NaN.

    sweep_trajectories.py --rotgen BUILD/rotgen --model MODELS/heavy_top.yaml
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

import h5py


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rotgen", required=True)
    ap.add_argument("--model", required=True)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "scene.yaml")
        text = (f"model: {a.model}\ninitial: {{phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}}\n"
                "time: {end: 1, samples: 11}\n"
                "integrator: {method: dop853, rtol: 1e-10, atol: 1e-12, max_steps: 150}\n"
                "record: [theta, body_z, energy]\n"
                "sweep:\n  mode: zip\n  vary:\n    initial.theta: {values: [0.3, 0.6, 0.9]}\n"
                "    initial.psi_dot: {values: [10, 20, 3000]}\n")
        with open(scene, "w") as f:
            f.write(text)
        out = os.path.join(tmp, "out")
        r = subprocess.run([a.rotgen, "sweep", scene, "-o", out, "--trajectories", "-q"],
                           capture_output=True, text=True)
        assert r.returncode == 3, (r.returncode, r.stderr)  # member 2 exceeds max_steps
        with open(os.path.join(out, "summary.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        h5 = h5py.File(os.path.join(out, "trajectories.h5"), "r")
        d = h5["trajectories"]
        columns = ["t", "theta", "body_z_x", "body_z_y", "body_z_z", "energy"]
        assert d.shape == (3, 11, len(columns)), d.shape
        assert d.dtype == "float64"
        assert [str(c) for c in d.attrs["columns"]] == columns, d.attrs["columns"]
        assert [str(k) for k in d.attrs["varied_keys"]] == ["initial.theta", "initial.psi_dot"]
        scene_attr = d.attrs["scene"]
        scene_attr = scene_attr.decode() if isinstance(scene_attr, bytes) else scene_attr
        assert scene_attr == text
        v = h5["varied_values"]
        assert v.shape == (3, 2)
        assert [list(x) for x in v[:]] == [[0.3, 10.0], [0.6, 20.0], [0.9, 3000.0]], v[:]
        for m, row in enumerate(rows):
            assert float(row["initial.theta"]) == v[m, 0]
            reached = [s for s in range(11) if not math.isnan(d[m, s, 0])]
            last = d[m, reached[-1], :]
            for c, name in enumerate(columns):
                assert float(row["final." + name]) == last[c], (m, name, row, last)
            # NaN exactly past the last sample reached
            assert reached == list(range(len(reached)))
            assert all(math.isnan(x) for x in d[m, len(reached):, :].flat)
        assert rows[0]["status"] == "ok" and rows[1]["status"] == "ok"
        assert rows[2]["status"].startswith("stopped at t = "), rows[2]["status"]
        assert len([s for s in range(11) if not math.isnan(d[2, s, 0])]) < 11
        # the time column is the sample grid
        assert [d[0, s, 0] for s in range(11)] == [s / 10 if s < 10 else 1.0 for s in range(11)]
    print("trajectories.h5: shape, attributes, varied values and final rows agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
