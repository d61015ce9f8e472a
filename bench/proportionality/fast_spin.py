#!/usr/bin/python3
"""The cost of an error with honest tolerances (issue 50): for each target error, the cheapest run
of each method (over rtol = atol on a grid) whose error over the samples (measure.py's: attitude
angle, |Δω| / |ω|, against taylor at 1e-15) is below the target and stays below it at every tighter
rtol; the time is `rotgen simulate`'s integrating time, the smallest of REPEATS (7) runs (the run
least disturbed by the machine's other work; the median of 3 differed by 1.4x between two
invocations on the 2-core machine).
    /usr/bin/python3 bench/proportionality/fast_spin.py [-o TABLE.md]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import measure  # noqa: E402

GRID = [10 ** (-k / 2) for k in range(8, 27)]  # 1e-4 … 1e-13 by half decades
REPEATS = 7
CASES = [  # scene, form or None, methods, targets
    ("bench/proportionality/fast_top.yaml", "body", ["dop853", "split2", "split4", "split6"],
     [1e-6, 1e-9]),
    ("bench/proportionality/fast_top.yaml", None, ["dop853", "taylor"], [1e-6, 1e-9]),
    ("models/scenes/free_top_workprecision.yaml", None, ["dop853", "taylor"], [1e-12]),
]


def timed(rotgen, path, method, tol, form, tmp):
    """(samples, smallest integrating time in ms) of one configuration."""
    scene, out = os.path.join(tmp, "s.yaml"), os.path.join(tmp, "o.csv")
    with open(scene, "w") as f:
        f.write(measure.scene_text(path, method, tol, form))
    times, data = [], None
    for _ in range(REPEATS):
        r = subprocess.run([rotgen, "simulate", scene, "-o", out], capture_output=True, text=True)
        if r.returncode != 0:
            return None, None
        m = re.search(r"time\s+([0-9.e+-]+) (ms|s|µs|us) integrating", r.stdout + r.stderr)
        scale = {"s": 1e3, "ms": 1.0, "µs": 1e-3, "us": 1e-3}[m.group(2)]
        times.append(float(m.group(1)) * scale)
    import numpy as np
    data = np.loadtxt(out, delimiter=",", comments="#", skiprows=2)
    return data, min(times)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-o", "--output", default="-")
    ap.add_argument("--rotgen", default=os.path.join(measure.ROOT, "build", "rotgen"))
    args = ap.parse_args()
    lines = []
    with tempfile.TemporaryDirectory() as tmp:
        for path, form, methods, targets in CASES:
            ref = measure.run(args.rotgen, path, "taylor", 1e-15, tmp, form)
            runs = {}
            for m in methods:
                runs[m] = []
                for tol in GRID:
                    data, ms = timed(args.rotgen, path, m, tol, form, tmp)
                    if data is not None:
                        runs[m].append((tol, measure.error(data, ref), ms))
            lines.append("\n%s, %s form: the cheapest run reaching each error (rtol, error, ms)\n"
                         % (path, form or "the scene's"))
            lines.append("| method | " + " | ".join("error %g" % t for t in targets) + " |")
            lines.append("|---|" + "---|" * len(targets))
            best = {}
            for m in methods:
                cells = []
                for t in targets:
                    ok = [r for i, r in enumerate(runs[m]) if all(e <= t for _, e, _ in runs[m][i:])]
                    if not ok:
                        cells.append("not reached")
                        continue
                    tol, e, ms = min(ok, key=lambda r: r[2])
                    best[(m, t)] = ms
                    cells.append("rtol %.2g: %.2g in %.3g ms" % (tol, e, ms))
                lines.append("| %s | %s |" % (m, " | ".join(cells)))
            for t in targets:
                others = [(best[(m, t)], m) for m in methods[1:] if (m, t) in best]
                if ("dop853", t) in best and others:
                    ms, m = min(others)
                    lines.append("\nat error %g: %s %.3g ms, dop853 %.3g ms: %.2fx DOP853's speed"
                                 % (t, m, ms, best[("dop853", t)], best[("dop853", t)] / ms))
            print("\n".join(lines[-8:]), file=sys.stderr, flush=True)
    text = "\n".join(lines) + "\n"
    if args.output == "-":
        sys.stdout.write(text)
    else:
        open(args.output, "w").write(text)


if __name__ == "__main__":
    main()
