#!/usr/bin/env bash
# Long runs: invariant drift over 10^6 steps, per integrator, with `rotgen simulate` (sparse
# samples: 1001, while the integrator takes ~10^6 steps). The work-precision harness
# (`rotgen bench`, bench/workprecision/) measures cost against accuracy; this is only the drift.
#   bench/extremes/long_runs.sh [path/to/rotgen]
# The heavy top of models/scenes/heavy_top_nutation.yaml (theta0 = 0.5, psi_dot = 30: nutation
# frequency I3 psi_dot / I1 = 15), in the Lagrangian form (y = q, q_dot) and the Hamiltonian form
# (y = q, p, where p_phi_dot = p_psi_dot = 0 is emitted as an exact 0). rk4 and the implicit midpoint
# rule take 10^6 steps of h = 0.01 (h omega_n = 0.15) over t in [0, 10^4]; dopri5 and dop853 at rtol
# 1e-10 atol 1e-12 over the span in which they take ~10^6 steps. Printed: the relative drift
# max |I(t) - I(0)| / |I(0)| over the samples up to 1/100, 1/10 and all of the span (~10^4, 10^5,
# 10^6 steps) for I = energy, p_phi, p_psi.
source "$(dirname "$0")/common.sh" "$@"

echo "| method | form | t end | steps (rejected) | RHS evals | energy drift at 1e4 / 1e5 / 1e6 steps | p_phi drift | p_psi drift |"
echo "|---|---|---:|---:|---:|---:|---:|---:|"
for spec in "rk4 h 0.01|10000|method: rk4, step: 0.01" \
            "implicit_midpoint h 0.01|10000|method: implicit_midpoint, step: 0.01" \
            "dopri5 rtol 1e-10|2800|method: dopri5, rtol: 1e-10, atol: 1e-12" \
            "dop853 rtol 1e-10|22000|method: dop853, rtol: 1e-10, atol: 1e-12"; do
  IFS='|' read -r name T integrator <<< "$spec"
  for form in lagrangian hamiltonian; do
    cat > "$work/scene.yaml" <<YAML
model: $root/models/heavy_top.yaml
form: $form
initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}
time: {end: $T, samples: 1001}
integrator: {$integrator}
record: [energy, p_phi, p_psi]
YAML
    if ! (cd "$work" && "$rotgen" simulate scene.yaml -o out.csv > summary 2>&1); then
      echo "| $name | $form | $T | fails: $(tail -1 "$work/summary" | cut -c1-60) | | | | |"
      continue
    fi
    steps=$(sed -n 's/.*steps   \([0-9]*\) accepted, \([0-9]*\) rejected.*/\1 (\2)/p' "$work/summary")
    evals=$(sed -n 's/.*; \([0-9]*\) RHS.*/\1/p' "$work/summary")
    drift=$(awk -F, 'function a(x) { return x < 0 ? -x : x }
      function cell(c, k) { return m[c, k] == 0 ? "0" : sprintf("%.1e", m[c, k] / a(v0[c])) }
      NR == 3 { for (c = 2; c <= 4; c++) v0[c] = $c }
      NR > 2 { for (c = 2; c <= 4; c++) { d = a($c - v0[c]); if (d > cur[c]) cur[c] = d }
               if (NR == 13 || NR == 103 || NR == 1003) for (c = 2; c <= 4; c++) m[c, NR - 1] = cur[c] }
      END { for (c = 2; c <= 4; c++) printf "%s / %s / %s%s", cell(c, 12), cell(c, 102), cell(c, 1002), c < 4 ? " | " : "" }' \
      "$work/out.csv")
    echo "| $name | $form | $T | $steps | $evals | $drift |"
  done
done
echo
echo "heavy top, theta0 = 0.5, psi_dot = 30; drift relative to the initial value, max over 1001 samples"
