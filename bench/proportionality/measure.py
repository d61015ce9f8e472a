#!/usr/bin/python3
"""Tolerance proportionality (issue 50, point 1): error ÷ rtol per method, scene and tolerance.

Runs `rotgen simulate` on each scene with every adaptive method at rtol = atol = 1e-5 … 1e-10 and
measures the largest error over the samples against a tight reference: the attitude angle between
the run's and the reference's quaternion, and |Δω| / |ω| (the larger of the two at each sample).
The reference is taylor at rtol = atol = 1e-15 in the scene's form; its distance to taylor at 1e-15
in another form (body, or lagrangian for a body scene), printed as the floor, bounds its own error
(cells within 10x of it are marked). DOP853 at 1e-14 is no reference here: on the fast top it is
8e-11 off both. Usage, from the repository root:
    /usr/bin/python3 bench/proportionality/measure.py [-o TABLE.md] [--rotgen build/rotgen]
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = {  # name -> (scene file, methods[, form (the scene's own when None)[, text edits]])
    "fast_top": ("bench/proportionality/fast_top.yaml",
                 ["dop853", "dopri5", "rosenbrock", "taylor", "split2", "split4", "split6"]),
    # the same top in the body form (quaternion, ω turning at 1000 rad/s): the split methods'
    # rows are fast_top's, which run the body form already
    "fast_top_body": ("bench/proportionality/fast_top.yaml",
                      ["dop853", "dopri5", "rosenbrock", "taylor"], "body"),
    # the same top spun at 10 rad/s, in the body form: few steps, where the fast top takes many
    "top_spin10_body": ("bench/proportionality/fast_top.yaml",
                        ["dop853", "dopri5", "rosenbrock", "taylor", "split2", "split4", "split6"],
                        "body", {"psi_dot: 1000": "psi_dot: 10"}),
    "heavy_top_nutation": ("models/scenes/heavy_top_nutation.yaml",
                           ["dop853", "dopri5", "rosenbrock", "taylor", "split2", "split4",
                            "split6"]),
    "free_top_workprecision": ("models/scenes/free_top_workprecision.yaml",
                               ["dop853", "dopri5", "rosenbrock", "taylor"]),
}
TOLS = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
RECORD = "[q0, q1, q2, q3, omega1, omega2, omega3]"


def scene_text(path, method, tol, form=None, edits=None):
    """The scene at `path` with its integrator, record, model path (form, edits) replaced."""
    text = open(os.path.join(ROOT, path)).read()
    for old, new in (edits or {}).items():
        text = text.replace(old, new)
    if form:
        text = re.sub(r"^form:.*$", "form: " + form, text, flags=re.M)
    model_dir = os.path.dirname(os.path.join(ROOT, path))
    text = re.sub(r"^model: (.*)$",
                  lambda m: "model: " + os.path.normpath(os.path.join(model_dir, m.group(1))),
                  text, flags=re.M)
    text = re.sub(r"^integrator:.*$",
                  "integrator: {method: %s, rtol: %g, atol: %g}" % (method, tol, tol),
                  text, flags=re.M)
    text = re.sub(r"^record:.*$", "record: " + RECORD, text, flags=re.M)
    text = re.sub(r"^events:(\n  .*)*", "", text, flags=re.M)
    return text


def run(rotgen, path, method, tol, tmp, form=None, edits=None):
    """The samples of one run (t, q0..q3, omega1..3) as an array, or None when it failed."""
    scene = os.path.join(tmp, "scene.yaml")
    out = os.path.join(tmp, "out.csv")
    with open(scene, "w") as f:
        f.write(scene_text(path, method, tol, form, edits))
    r = subprocess.run([rotgen, "simulate", scene, "-o", out, "--quiet"],
                       capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        sys.stderr.write("%s %s %g: %s\n" % (path, method, tol, r.stderr.strip()))
        return None
    return np.loadtxt(out, delimiter=",", comments="#", skiprows=2)


def error(a, ref):
    """Largest over the samples of max(attitude angle, |Δω| / |ω|)."""
    q, qr = a[:, 1:5], ref[:, 1:5]
    s = np.sign(np.sum(q * qr, axis=1))[:, None]
    s[s == 0] = 1
    chord = np.linalg.norm(q - s * qr, axis=1)
    angle = 4 * np.arcsin(np.minimum(chord / 2, 1))
    w, wr = a[:, 5:8], ref[:, 5:8]
    rel = np.linalg.norm(w - wr, axis=1) / np.maximum(np.linalg.norm(wr, axis=1), 1e-300)
    return float(np.max(np.maximum(angle, rel)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-o", "--output", default="-")
    ap.add_argument("--rotgen", default=os.path.join(ROOT, "build", "rotgen"))
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--methods", default="", help="only these (comma-separated)")
    args = ap.parse_args()
    lines = ["| scene | method | " + " | ".join("%g" % t for t in TOLS) +
             " | spread (max/min) |", "|---|---|" + "---:|" * (len(TOLS) + 1)]
    notes = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.scenes.split(","):
            path, methods, form, edits = (SCENES[name] + (None, None))[:4]
            ref = run(args.rotgen, path, "taylor", 1e-15, tmp, form, edits)
            own = form or re.search(r"^form: (\w+)", open(os.path.join(ROOT, path)).read(),
                                    flags=re.M).group(1)
            other = "lagrangian" if own == "body" else "body"
            floor = error(run(args.rotgen, path, "taylor", 1e-15, tmp, other, edits), ref)
            notes.append("%s: reference taylor 1e-15; taylor at 1e-15 in the %s form differs by "
                         "%.1e (the floor)" % (name, other, floor))
            for m in methods:
                if args.methods and m not in args.methods.split(","):
                    continue
                cells, ratios = [], []
                for tol in TOLS:
                    a = run(args.rotgen, path, m, tol, tmp, form, edits)
                    if a is None:
                        cells.append("failed")
                        continue
                    e = error(a, ref)
                    ratios.append(e / tol)
                    mark = " (floor)" if e < 10 * floor else ""
                    cells.append("%.3g%s" % (e / tol, mark))
                spread = max(ratios) / min(ratios) if ratios else float("nan")
                lines.append("| %s | %s | %s | %.3g |" % (name, m, " | ".join(cells), spread))
                print(lines[-1], file=sys.stderr, flush=True)
    text = "\n".join(lines) + "\n\n" + "\n".join("- " + n for n in notes) + "\n"
    if args.output == "-":
        sys.stdout.write(text)
    else:
        open(args.output, "w").write(text)


if __name__ == "__main__":
    main()
