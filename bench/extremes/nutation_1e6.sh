#!/usr/bin/env bash
# The fast-spin nutation at omega3 = 1e6 (bench/extremes/fast_spin.sh's top: models/heavy_top.yaml,
# g = 10, theta0 = 0.5, Lagrangian form, t in [0, 1], 1001 samples) under dop853 at several
# tolerances: RHS evaluations, the nutation amplitude on [1/2, 1] over the exact one (1: resolved,
# 0: lost) and phi(1)'s error against fast_spin.sh's long-double reference 1.99999928866837587e-06.
# Measures what the error layout (generator/run/tolerance_layout.hpp) does to it:
#   bench/extremes/nutation_1e6.sh [path/to/rotgen]      (bench/results/euler_rate_groups.md)
source "$(dirname "$0")/common.sh" "$@"
echo "| rtol | atol | RHS evals | nutation amplitude / exact | phi(1) rel. error |"
echo "|---:|---:|---:|---:|---:|"
for spec in "1e-10 1e-10" "1e-12 1e-12" "1e-13 1e-15" "1e-14 1e-16"; do
  set -- $spec
  cat > "$work/scene.yaml" <<YAML
model: $root/models/heavy_top.yaml
parameters: {g: 10}
form: lagrangian
initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 1e6}
time: {end: 1, samples: 1001}
integrator: {method: dop853, rtol: $1, atol: $2}
record: [theta, phi]
YAML
  evals=$(cd "$work" && "$rotgen" simulate scene.yaml -o out.csv 2>&1 | sed -n 's/.*; \([0-9]*\) RHS.*/\1/p')
  /usr/bin/python3 - "$work/out.csv" "$1" "$2" "$evals" <<'PY'
import math, sys
import numpy as np
d = np.genfromtxt(sys.argv[1], delimiter=",", names=True, skip_header=1)
c = 8 / 1e12; x = c * math.sin(0.5)  # exact theta1 - theta0 (fast_spin.sh's Newton iteration)
for _ in range(30):
    a = 0.5 + x
    x -= (2 * math.sin(0.5 + x / 2) * math.sin(x / 2) - c * math.sin(a) ** 2) / \
         (math.sin(a) - 2 * c * math.sin(a) * math.cos(a))
late = d["t"] >= 0.5
amp = (d["theta"][late].max() - d["theta"][late].min()) / x
ref = 1.99999928866837587e-06
print("| %s | %s | %s | %.4f | %.1e |" % (sys.argv[2], sys.argv[3], sys.argv[4], amp,
                                            abs(d["phi"][-1] - ref) / ref))
PY
done
