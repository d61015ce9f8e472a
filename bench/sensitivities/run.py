"""The cost of sensitivities (issue 48) on the heavy top: one run integrating y (+) S for k keys
against the 2k + 1 runs of central differences, k = 1, 4, 11 (all 6 initial values and all 5
parameters), over 10 time units (1001 samples).

The integration time is the engine's own (summary integrate_seconds: no derivation, no compiling),
the least of 15 repeats: on a shared machine a run of a few milliseconds is often descheduled
while one of 0.1 ms is not, so a median charges the one long run (sensitivities) for other
processes' load and not the 2k + 1 short ones; the least time is the run's own cost.
Sensitivities run at rtol 1e-8 (about the accuracy central differences reach), 1e-10 and 1e-12;
central differences at rtol 1e-13 with h = 1e-5 max(|value|, 0.1), where their derivative is good
to about 1e-7 (the tests' own finite differences). Each derivative's error is measured against
the sensitivities at rtol 1e-13 (max over samples and columns, relative to max(|d|, 1e-3)); the
last column is the time over that of the 2k + 1 runs (the issue's goal: below 0.5).

    PYTHONPATH=build/python /usr/bin/python3 bench/sensitivities/run.py \
        > bench/results/sensitivities.csv
"""

import os
import sys
import tempfile

import numpy as np

import rotgen

HERE = os.path.dirname(os.path.abspath(__file__))
MODEL = os.path.join(HERE, "..", "..", "models", "heavy_top.yaml")
INITIAL = {"phi": 0.0, "theta": 0.5, "psi": 0.0, "phi_dot": 0.3, "theta_dot": 0.1, "psi_dot": 5.0}
PARAMETERS = {"I1": 1.0, "I3": 0.5, "M": 1.0, "g": 9.81, "h": 0.1}
KEYS = {
    1: ["parameters.h"],
    4: ["initial.theta", "initial.psi_dot", "parameters.h", "parameters.I3"],
    11: [f"initial.{n}" for n in INITIAL] + [f"parameters.{n}" for n in PARAMETERS],
}


def scene(rtol, keys=None, initial=INITIAL, parameters=PARAMETERS):
    init = ", ".join(f"{k}: {v!r}" for k, v in initial.items())
    par = ", ".join(f"{k}: {v!r}" for k, v in parameters.items())
    text = (f"model: {MODEL}\nform: lagrangian\nparameters: {{{par}}}\ninitial: {{{init}}}\n"
            "time: {start: 0, end: 10, samples: 1001}\n"
            f"integrator: {{method: dop853, rtol: {rtol}, atol: {rtol * 1e-2}}}\n"
            "record: [theta, phi, theta_dot, energy]\nswitch_chart: false\n")
    if keys:
        text += "sensitivities: [" + ", ".join(keys) + "]\n"
    f = tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False)
    f.write(text)
    f.close()
    return f.name


def timed(path, repeats=15):
    rotgen.simulate(path)  # compiled or loaded once
    times, r = [], None
    for _ in range(repeats):
        r = rotgen.simulate(path)
        times.append(r.summary["integrate_seconds"])
    return min(times), r


def moved(key, delta):
    group, name = key.split(".")
    initial, parameters = dict(INITIAL), dict(PARAMETERS)
    (initial if group == "initial" else parameters)[name] += delta
    return initial, parameters


def error(d, reference):
    return float(np.nanmax(np.abs(d - reference) / np.maximum(np.abs(reference), 1e-3)))


def differences(keys, ref):
    """The 2k + 1 runs of central differences: their summed time and their derivative's error."""
    total, _ = timed(scene(1e-13))
    fd = np.empty_like(ref.sensitivities)
    for j, key in enumerate(keys):
        group, name = key.split(".")
        x = (INITIAL if group == "initial" else PARAMETERS)[name]
        h = 1e-5 * max(abs(x), 0.1)
        up, r_up = timed(scene(1e-13, None, *moved(key, h)))
        down, r_down = timed(scene(1e-13, None, *moved(key, -h)))
        total += up + down
        fd[:, :, j] = (r_up.y - r_down.y) / (2 * h)
    return total, error(fd, ref.sensitivities)


def main():
    print("k,method,rtol,runs,integrate_seconds,max_error,time_vs_differences")
    for k, keys in KEYS.items():
        _, ref = timed(scene(1e-13, keys), 1)
        rows = []
        for rtol in (1e-8, 1e-10, 1e-12):
            t, r = timed(scene(rtol, keys))
            rows.append((rtol, t, error(r.sensitivities, ref.sensitivities)))
        total, e = differences(keys, ref)
        for rtol, t, e_s in rows:
            print(f"{k},sensitivities,{rtol},1,{t:.6g},{e_s:.3g},{t / total:.3g}")
        print(f"{k},central_differences,1e-13,{2 * k + 1},{total:.6g},{e:.3g},1")
        sys.stdout.flush()

if __name__ == "__main__":
    main()
