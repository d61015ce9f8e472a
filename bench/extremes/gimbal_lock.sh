#!/usr/bin/env bash
# Gimbal lock: how the Euler-angle forms fail as a trajectory approaches theta = 0.
#   bench/extremes/gimbal_lock.sh [path/to/rotgen]
# A free symmetric top (I1 = I2 = 2, I3 = 1; omega = (0.3, 0, 1) in body axes) is started with its
# symmetry axis at angle delta from the space vertical, in the plane of the vertical and the angular
# momentum, so that delta is its closest approach; it returns there once per precession period
# (4 pi / |omega3| ~ 12.6). Exact: omega1 + i omega2 = 0.3 exp(i Omega t), Omega = (I3 - I1)/I1
# omega3 = -1/2, omega3 = 1. Printed: the max error of omega over t in [0, 40] for the Lagrangian
# and Hamiltonian forms kept in the chart (switch_chart: false), with the automatic switch to the
# body form, and the body form itself; and the RHS evaluations each needed (dop853, rtol 1e-10).
source "$(dirname "$0")/common.sh" "$@"
cat > "$work/model.yaml" <<'YAML'
name: symmetric_free_top
parameters: {I1: 2, I3: 1}
inertia: [I1, I1, I3]
YAML
run() { # form switch delta -> "error evals"
  cat > "$work/scene.yaml" <<YAML
model: model.yaml
form: $1
switch_chart: $2
initial: {phi: 0, theta: $3, psi: 1.5707963267948966, omega1: 0.3, omega2: 0, omega3: 1}
time: {end: 40, samples: 4001}
integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}
record: [omega1, omega2, omega3]
YAML
  if out=$("$rotgen" simulate "$work/scene.yaml" -o "$work/out.csv" 2>&1); then
    evals=$(echo "$out" | sed -n 's/.*; \([0-9]*\) RHS.*/\1/p')
    err=$(awk -F, 'NR > 2 { e1 = $2 - 0.3*cos(-0.5*$1); e2 = $3 - 0.3*sin(-0.5*$1); e3 = $4 - 1;
                   m = sqrt(e1*e1) > m ? sqrt(e1*e1) : m; m = sqrt(e2*e2) > m ? sqrt(e2*e2) : m;
                   m = sqrt(e3*e3) > m ? sqrt(e3*e3) : m } END { printf "%.2e", m }' "$work/out.csv")
    echo "$err ($evals)"
  else
    echo "fails: $(echo "$out" | tail -1 | sed 's/.*stopped: //' | cut -c1-40)"
  fi
}
echo "| closest approach delta | Lagrangian, chart kept | Hamiltonian, chart kept | Lagrangian, auto switch | body form |"
echo "|---:|---:|---:|---:|---:|"
for delta in 1e-1 1e-2 1e-3 1e-4 1e-5 1e-6 1e-7 1e-8; do
  echo "| $delta | $(run lagrangian false $delta) | $(run hamiltonian false $delta) | $(run lagrangian true $delta) | $(run body true $delta) |"
done
echo
echo "max |omega - exact| over t in [0, 40] (RHS evaluations); dop853, rtol 1e-10, atol 1e-12"
