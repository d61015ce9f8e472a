#!/usr/bin/python3
"""The falling top's fall time (models/scenes/falling_top.yaml) four ways, for the README's tour.

    /usr/bin/python3 bench/falling_top.py build/rotgen > bench/results/falling_top.md

The heavy top released at theta0 = 0.3 with no spin falls as a pendulum: (1/2) I1 theta_dot^2 =
M g h (cos theta0 - cos theta) (5.73), so the time to reach theta is, with k = cos(theta0 / 2) and
w = sqrt(M g h / I1),
    t(theta) = (K(k) - F(asin(cos(theta / 2) / k), k)) / w
(K, F the complete and incomplete elliptic integrals of the first kind, modulus k). Printed: that
formula in double (SciPy's ellipk/ellipkinc, parameter m = k^2) and in 30 digits (mpmath), SciPy's
solve_ivp with DOP853 at rtol = atol = 1e-13 on the top's equations (by tests/python/events_scipy.py,
for floor: a terminal event at theta = pi/2), and `rotgen simulate` of the shipped scene (its event `floor`).
Needs python3-scipy and python3-mpmath.
"""
import csv
import math
import os
import subprocess
import sys
import tempfile

import mpmath
from scipy.special import ellipk, ellipkinc

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "python"))
import events_scipy  # noqa: E402  (SciPy's solve_ivp on the heavy top's equations)

I1, M, G, H = 1.0, 1.0, 9.81, 0.1  # models/heavy_top.yaml
THETA0 = 0.3                       # models/scenes/falling_top.yaml


def elliptic_double(theta):
    k, w = math.cos(THETA0 / 2), math.sqrt(M * G * H / I1)
    return (ellipk(k * k) - ellipkinc(math.asin(math.cos(theta / 2) / k), k * k)) / w


def elliptic_mpmath(theta):
    mpmath.mp.dps = 30
    k = mpmath.cos(mpmath.mpf(THETA0) / 2)
    w = mpmath.sqrt(mpmath.mpf(M) * mpmath.mpf(G) * mpmath.mpf(H) / mpmath.mpf(I1))
    return (mpmath.ellipk(k**2) - mpmath.ellipf(mpmath.asin(mpmath.cos(theta / 2) / k), k**2)) / w


def scipy_dop853(name):
    """SciPy's time of `floor`, by the test's own code (the top's four equations)."""
    return repr(events_scipy.scipy_floor(THETA0, 0.0)["t"]) if name == "floor" else "-"


def rotgen_events(rotgen):
    scene = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "models", "scenes",
                         "falling_top.yaml")
    with tempfile.TemporaryDirectory() as work:
        out = os.path.join(work, "fall.csv")
        subprocess.run([rotgen, "simulate", scene, "-o", out, "-q"], check=True)
        with open(os.path.join(work, "fall.events.csv")) as f:
            rows = (line for line in f if not line.startswith("#"))  # the "# rotgen ..." line
            return {r["event"]: float(r["t"]) for r in csv.DictReader(rows)}


def main():
    rotgen = sys.argv[1] if len(sys.argv) > 1 else "build/rotgen"
    events = rotgen_events(rotgen)
    print("# The falling top's fall time\n")
    print("Written by `/usr/bin/python3 bench/falling_top.py build/rotgen > "
          "bench/results/falling_top.md` (models/scenes/falling_top.yaml: theta0 = 0.3, no spin).\n")
    print("| event | elliptic integral, double (SciPy) | elliptic integral, 30 digits (mpmath) "
          "| SciPy solve_ivp DOP853 rtol 1e-13 | rotgen simulate (DOP853 rtol 1e-12) "
          "| rotgen - 30 digits |")
    print("|---|---|---|---|---|---|")
    for name, theta in (("halfway", math.pi / 4), ("floor", math.pi / 2)):
        exact = elliptic_mpmath(mpmath.pi / (4 if name == "halfway" else 2))
        print(f"| {name} (theta = {'pi/4' if name == 'halfway' else 'pi/2'}) "
              f"| {elliptic_double(theta)!r} | {mpmath.nstr(exact, 20)} | {scipy_dop853(name)} "
              f"| {events[name]!r} | {float(events[name] - exact):.2e} |")


if __name__ == "__main__":
    main()
