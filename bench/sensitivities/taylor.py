#!/usr/bin/python3
"""The Taylor method with sensitivities against DOP853 with the same keys, through `rotgen
simulate` (the run engine: Taylor expands the recurrences of (y, S), run/taylor_sensitivity.hpp;
DOP853 integrates the variational equations, run/sensitivity_run.cpp).

    /usr/bin/python3 bench/sensitivities/taylor.py build/rotgen > bench/results/taylor_sensitivities.md

The heavy top (Lagrangian form), the nutating start of bench/sensitivities/run.sh, t = 0..50,
501 samples, k = 4 keys (h, I3, M, g), rtol = 1e-12, atol = 1e-14. Time: simulate's
`time ... integrating` (kernels compiled before, from the cache), median of REPEATS runs, the
methods interleaved. Error: the largest |d - d_ref| / max(1e-3, |d_ref|) over the d(...) columns of every
sample, d_ref from DOP853 at rtol 1e-14, atol 1e-16. The first run of each method compiles its
kernels in an empty cache: its wall time is the compiler's (Taylor's augmented recurrences are the
larger unit).
"""
import csv
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROTGEN = os.path.realpath(sys.argv[1] if len(sys.argv) > 1 else "build/rotgen")
REPEATS = int(os.environ.get("REPEATS", "7"))
ROOT = os.path.realpath(os.path.join(os.path.dirname(__file__), "..", ".."))
KEYS = "[parameters.h, parameters.I3, parameters.M, parameters.g]"

SCENE = """model: {root}/models/heavy_top.yaml
form: lagrangian
initial: {{phi: 0.1, theta: 0.5, psi: 0, phi_dot: 0.3, theta_dot: 0.2, psi_dot: 10}}
time: {{start: 0, end: 50, samples: 501}}
integrator: {{method: {method}, rtol: {rtol}, atol: {atol}}}
record: [theta, theta_dot, psi_dot]
switch_chart: false
sensitivities: {keys}
"""


def run(work, method, rtol, atol, env=None):
    scene = os.path.join(work, "%s_%g.yaml" % (method, rtol))
    with open(scene, "w") as f:
        f.write(SCENE.format(root=ROOT, method=method, rtol=rtol, atol=atol, keys=KEYS))
    out = os.path.join(work, "out.csv")
    p = subprocess.run([ROTGEN, "simulate", scene, "-o", out],
                       capture_output=True, text=True, check=True, env=env)
    unit = {"s": 1.0, "ms": 1e-3, "µs": 1e-6, "us": 1e-6, "ns": 1e-9}
    seconds = [float(w[1]) * unit[w[2]] for w in (line.split() for line in p.stdout.splitlines())
               if len(w) > 3 and w[0] == "time" and w[3].startswith("integrating")]
    steps = [line.split()[1] for line in p.stdout.splitlines() if line.strip().startswith("steps")]
    with open(out) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    header, rows = rows[0], [[float(x) for x in r] for r in rows[1:]]
    d = [i for i, name in enumerate(header) if name.startswith("d(")]
    return sum(seconds), int(steps[0]) if steps else 0, [[r[i] for i in d] for r in rows]


def error(values, reference):
    return max(abs(a - b) / max(1e-3, abs(b))
               for row, ref in zip(values, reference) for a, b in zip(row, ref))


def main():
    with tempfile.TemporaryDirectory() as work:
        _, _, reference = run(work, "dop853", 1e-14, 1e-16)
        times = {"taylor": [], "dop853": []}
        result = {}
        fresh = dict(os.environ, ROTGEN_CACHE_DIR=os.path.join(work, "cache"))
        compile_s = {}
        for method in times:  # compile once, in an empty cache: the wall time of that first run
            start = time.perf_counter()
            result[method] = run(work, method, 1e-12, 1e-14, fresh)
            compile_s[method] = time.perf_counter() - start
        for _ in range(REPEATS):
            for method in times:
                times[method].append(run(work, method, 1e-12, 1e-14, fresh)[0])
    load = open("/proc/loadavg").read().split()[0]
    print("# The Taylor method with sensitivities against DOP853\n")
    print("`/usr/bin/python3 bench/sensitivities/taylor.py build/rotgen` (this file's generator; "
          "its docstring says what is measured). The heavy top, Lagrangian form, t = 0..50, "
          "k = 4 keys (h, I3, M, g), rtol 1e-12, atol 1e-14; time: integrating, median "
          "of %d runs, the methods interleaved; error of the d(...) columns at every sample "
          "against DOP853 at rtol 1e-14.\n" % REPEATS)
    print("| method | steps | integrate ms (median) | min ms | max ms | error of d(...) "
          "| first run, compiling (s) |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for method in times:
        t = times[method]
        print("| %s | %d | %.2f | %.2f | %.2f | %.1e | %.1f |" % (
            method, result[method][1], 1e3 * statistics.median(t), 1e3 * min(t), 1e3 * max(t),
            error(result[method][2], reference), compile_s[method]))
    ratio = statistics.median(times["taylor"]) / statistics.median(times["dop853"])
    fastest = min(times["taylor"]) / min(times["dop853"])
    print("\nTaylor ÷ DOP853: %.2f (medians), %.2f (fastest runs)\n" % (ratio, fastest))
    print("Measured on %d cores, load %s (a shared machine: compare the ratio, not the times)."
          % (os.cpu_count(), load))


if __name__ == "__main__":
    main()
