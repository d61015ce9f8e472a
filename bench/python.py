#!/usr/bin/env python3
"""rotgen from Python against the CLI, in one command (Markdown on stdout):

    PYTHONPATH=build/python /usr/bin/python3 bench/python.py build/rotgen > bench/results/python.md

1. A 1,000-member sweep (the heavy top, initial theta 0.1 .. 1.5, t = 0 .. 10, 101 samples,
   DOP853 rtol 1e-10) started from Python (rotgen.sweep) and through the CLI (rotgen sweep): the
   "running the members" time of each (the CLI's `--timings` line `members`, the Python result's
   `seconds`: the same span, around the pool of members), medians of 7 runs, the two interleaved
   (one of each in turn), the kernels compiled once before (a warm cache of its own). On 1 thread
   and on 2 without trajectories, and on 2 with them (the CLI's --trajectories streams them to
   its HDF5 file within the span; Python copies them into one array). Goal: Python at most 10%
   more.
2. Two Python threads each running rotgen.simulate (the nutating top to t = 20000) at once against
   one: the GIL is released while members integrate, so on 2 cores two take about as long as one.
   Medians of 7, interleaved. Goal (the issue's): two in less than 1.6x one.
3. A pure-Python loop on the calling thread, alone and while simulate runs on another thread.
Timing claims live here, never in ctest.
"""

import os
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time

import rotgen

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
MEMBERS = 1000
RUNS = 7  # of each, interleaved
SIMULATE_END = 20000  # the two-thread simulate
CONFIGS = [(1, False), (2, False), (2, True)]  # (threads, trajectories kept)


def scene_text(end):
    return f"""model: {ROOT}/models/heavy_top.yaml
initial: {{phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}}
time: {{start: 0, end: {end}, samples: 101}}
integrator: {{method: dop853, rtol: 1e-10, atol: 1e-12}}
record: [theta, energy]
sweep:
  vary:
    initial.theta: {{from: 0.1, to: 1.5, count: {MEMBERS}}}
"""


def cli_members_seconds(rotgen_exe, scene, out, threads, trajectories):
    args = [rotgen_exe, "sweep", scene, "-o", out, "-j", str(threads), "--quiet", "--timings"]
    if trajectories:
        args.append("--trajectories")
    p = subprocess.run(args, capture_output=True, text=True, check=True)
    return float(re.search(r"rotgen: timing members\s+([0-9.]+) s", p.stderr).group(1))


def sweep_rows(rotgen_exe, work):
    scene = os.path.join(work, "sweep.yaml")
    with open(scene, "w") as f:
        f.write(scene_text(10))
    out = os.path.join(work, "out")
    rotgen.sweep(scene, threads=1)  # compiles the kernels into the cache
    rows = []
    for threads, trajectories in CONFIGS:
        cli, py = [], []
        for _ in range(RUNS):
            cli.append(cli_members_seconds(rotgen_exe, scene, out, threads, trajectories))
            py.append(rotgen.sweep(scene, threads=threads, trajectories=trajectories).seconds)
        c, p = statistics.median(cli), statistics.median(py)
        rows.append((threads, trajectories, c, p, min(cli), min(py)))
        print(f"sweep: {threads} threads, trajectories {trajectories}: CLI {c:.4f} s, "
              f"Python {p:.4f} s", file=sys.stderr)
    return rows


def threads_rows(work):
    scene = rotgen.Scene(yaml_text=scene_text(SIMULATE_END))
    rotgen.simulate(scene)  # compiled and cached
    one, two, integrating = [], [], []
    for _ in range(RUNS):
        start = time.perf_counter()
        r = rotgen.simulate(scene)
        one.append(time.perf_counter() - start)
        integrating.append(r.summary["integrate_seconds"] / one[-1])
        pair = [threading.Thread(target=rotgen.simulate, args=(scene,)) for _ in range(2)]
        start = time.perf_counter()
        for t in pair:
            t.start()
        for t in pair:
            t.join()
        two.append(time.perf_counter() - start)
    return statistics.median(one), statistics.median(two), one, two, statistics.median(integrating)


def spin(seconds):
    """Iterations of a pure-Python loop in `seconds` of wall time."""
    n, end = 0, time.perf_counter() + seconds
    while time.perf_counter() < end:
        n += 1
    return n


def gil_rows():
    """Python's own work on the calling thread, alone and while rotgen.simulate runs on another
    thread (had simulate held the GIL, the loop would stop for the whole call): iterations a
    second, medians of RUNS, interleaved."""
    scene = rotgen.Scene(yaml_text=scene_text(SIMULATE_END))
    alone, beside = [], []
    for _ in range(RUNS):
        alone.append(spin(0.5) / 0.5)
        worker = threading.Thread(target=rotgen.simulate, args=(scene,))
        worker.start()
        time.sleep(0.1)  # past its preparation, into the integration
        beside.append(spin(0.5) / 0.5)
        worker.join()
    return statistics.median(alone), statistics.median(beside)


START_LOAD = " ".join(f"{x:.2f}" for x in os.getloadavg())


def main():
    rotgen_exe = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "build/rotgen")
    with tempfile.TemporaryDirectory() as work:
        os.environ["ROTGEN_CACHE_DIR"] = os.path.join(work, "cache")
        rows = sweep_rows(rotgen_exe, work)
        one, two, ones, twos, integrating = threads_rows(work)
        alone, beside = gil_rows()
    load = " ".join(f"{x:.2f}" for x in os.getloadavg())
    start_load = START_LOAD
    print("# rotgen from Python against the CLI\n")
    print("`PYTHONPATH=build/python /usr/bin/python3 bench/python.py build/rotgen > "
          "bench/results/python.md`;")
    print(f"{os.cpu_count()} cores, load average {start_load} when it started and {load} when it "
          "finished (1, 5, 15 minutes; the machine is shared with other builds and tests: medians "
          "of interleaved runs, which still move with the load).\n")
    print(f"## A {MEMBERS}-member sweep: `rotgen.sweep` against `rotgen sweep`\n")
    print(f"The heavy top, initial theta 0.1 .. 1.5, t = 0 .. 10, 101 samples, DOP853 rtol 1e-10, "
          "records theta and energy; the time is \"running the members\" (the CLI's `--timings` "
          f"line `members`, the Python result's `seconds`), median of {RUNS} runs interleaved (min in "
          "brackets), kernels cached.\n")
    print("| threads | trajectories kept | CLI s | Python s | Python / CLI (goal <= 1.10) |")
    print("|---:|---|---:|---:|---:|")
    for threads, traj, c, p, cmin, pmin in rows:
        print(f"| {threads} | {'yes' if traj else 'no'} | {c:.4f} ({cmin:.4f}) | "
              f"{p:.4f} ({pmin:.4f}) | {p / c:.3f} |")
    print("\n## Two Python threads running `rotgen.simulate` at once\n")
    print(f"The nutating top (DOP853, rtol 1e-10) to t = {SIMULATE_END}, 101 samples; wall time "
          "of one call alone against two calls on two Python threads started together, median "
          f"of {RUNS}, interleaved. A call alone spends {100 * integrating:.0f}% of its time "
          "integrating (median; the GIL released), the rest reading, deriving and loading the "
          "cached kernels under the one GiNaC lock, which the two calls take in turn.\n")
    print("| one simulate s | two at once s | ratio (goal < 1.6) |")
    print("|---:|---:|---:|")
    print(f"| {one:.3f} | {two:.3f} | {two / one:.2f} |")
    print("\nRuns, one: " + ", ".join(f"{x:.3f}" for x in ones) +
          "; two: " + ", ".join(f"{x:.3f}" for x in twos) + ".")
    print("\n## Python's own thread while `rotgen.simulate` integrates\n")
    print("Iterations a second of a pure-Python loop on the calling thread, alone and while the "
          "same simulate runs on a second Python thread (from 0.1 s into the call, for 0.5 s); "
          f"median of {RUNS}, interleaved. Had the call held the GIL, the loop would stand still "
          "for the whole call; on a loaded machine the two threads also share the cores.\n")
    print("| loop alone /s | loop beside simulate /s | ratio |")
    print("|---:|---:|---:|")
    print(f"| {alone:.3g} | {beside:.3g} | {beside / alone:.2f} |")


if __name__ == "__main__":
    main()
