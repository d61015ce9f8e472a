#!/usr/bin/env bash
# Fast spin: the heavy top (models/heavy_top.yaml with g = 10, so that the gravity frequency
# omega_g = sqrt(M g h / I1) = 1 and the spin ratio omega3/omega_g is omega3 itself), released at
# theta0 = 0.5 with phi_dot = theta_dot = 0 and psi_dot = omega3 = 1e2 ... 1e6.
#   bench/extremes/fast_spin.sh [path/to/rotgen]
#
# Nutation amplitude, exact: with u = cos(theta), p_psi = I3 omega3 and p_phi = p_psi cos(theta0),
# the effective potential of (5.79), V'(theta) = (p_phi - p_psi cos theta)^2 / (2 I1 sin^2 theta)
# + M g h cos theta, equals the energy V'(theta0) = M g h cos theta0 again where
#   u0 - u1 = c (1 - u1^2),   c = 2 I1 M g h / p_psi^2,
# solved below by Newton's method in theta1 - theta0 (no cancellation). Fast-top estimate (c << 1):
#   delta_theta = theta1 - theta0 ~ c sin(theta0) = 2 I1 M g h sin(theta0) / (I3 omega3)^2,
# nutation frequency I3 omega3 / I1, mean precession rate M g h / (I3 omega3).
#
# Table 1: dop853 (rtol 1e-10, atol 1e-12) over 20 nutation periods, 1000 samples per period, in
# the Lagrangian, Hamiltonian and body forms: the sampled max(theta) - theta0 against the exact
# delta_theta, RHS evaluations per unit time (with the dense output's 3 extra per step), and the
# Lagrangian form's invariant drift (the Hamiltonian form keeps p_phi, p_psi exactly: p_dot = 0).
# Table 2: omega3 = 1e6 (and 1e5) over t in [0, 1] (80,000 nutation periods), explicit dop853
# against RODAS4 and the implicit midpoint rule, Lagrangian form; phi(1) against a long-double
# dop853 run at rtol 1e-17 (fast_spin_reference.cpp, ~10 s CPU at 1e6).
source "$(dirname "$0")/common.sh" "$@"
g++ -O2 -std=c++17 -I generated -I runtime -I /usr/include/eigen3 bench/extremes/fast_spin_reference.cpp \
    -o "$work/reference"

awk_lib='
function exact_dtheta(w,   c, d, i, a) {  # theta1 - theta0 for I1 = 1, I3 = 0.5, M g h = 1
  c = 8 / (w*w); d = c*sin(0.5)
  for (i = 0; i < 30; i++) {  # Newton on 2 sin(t0 + d/2) sin(d/2) - c sin^2(t0 + d) = 0 (u0 - u1 = c (1 - u1^2))
    a = 0.5 + d
    d -= (2*sin(0.5 + d/2)*sin(d/2) - c*sin(a)^2) / (sin(a) - 2*c*sin(a)*cos(a))
  }
  return d
}'

# run FORM OMEGA3 T SAMPLES "INTEGRATOR" -> the summary in $work/summary, the CSV in $work/out.csv
run() {
  cat > "$work/scene.yaml" <<YAML
model: $root/models/heavy_top.yaml
parameters: {g: 10}
form: $1
initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: $2}
time: {end: $3, samples: $4}
integrator: {$5}
record: [theta, phi, energy, p_phi, p_psi]
YAML
  (cd "$work" && "$rotgen" simulate scene.yaml -o out.csv > summary 2>&1) || {
    echo "failed: $(tail -1 "$work/summary")" >&2
    return 1
  }
}
field() { sed -n "$1" "$work/summary"; }
evals() { field 's/.*; \([0-9]*\) RHS.*/\1/p'; }
relative() { field "s/.*drift   $1: .*(relative \([^)]*\)).*/\1/p"; }

echo "| omega3/omega_g | exact delta_theta | fast-top estimate, rel. diff | Lagrangian: delta_theta rel. error, RHS evals per unit time | drift p_phi / p_psi / energy (relative) | Hamiltonian: delta_theta rel. error, evals per unit time | body form: delta_theta rel. error, evals per unit time |"
echo "|---:|---:|---:|---:|---:|---:|---:|"
for w in 1e2 1e3 1e4 1e5 1e6; do
  T=$(awk -v w=$w 'BEGIN { printf "%.17g", 20*2*3.141592653589793/(0.5*w) }')
  exact=$(awk -v w=$w "$awk_lib"' BEGIN { printf "%.17g", exact_dtheta(w) }')
  est=$(awk -v w=$w -v e=$exact 'BEGIN { printf "%.4e | %.1e", e, (8*sin(0.5)/(w*w) - e)/e }')
  cells=()
  for form in lagrangian hamiltonian body; do
    run $form $w $T 20001 "method: dop853, rtol: 1e-10, atol: 1e-12"
    err=$(awk -F, -v e=$exact 'NR > 2 { if ($2 > m) m = $2 } END { d = (m - 0.5 - e)/e; printf "%.1e", d < 0 ? -d : d }' "$work/out.csv")
    cells+=("$err, $(awk -v n=$(evals) -v T=$T 'BEGIN { printf "%.2e", n/T }')")
    [ $form = lagrangian ] && drift="$(relative p_phi) / $(relative p_psi) / $(relative energy)"
  done
  echo "| $w | $est | ${cells[0]} | $drift | ${cells[1]} | ${cells[2]} |"
done
echo
echo "dop853 rtol 1e-10 atol 1e-12, t in [0, 20 nutation periods], 1000 samples per period; g = 10 so omega_g = 1"
echo

for w in 1e5 1e6; do
  read -r ref_phi ref_lo ref_hi ref_evals < <("$work/reference" $w 1)
  echo "omega3 = $w, t in [0, 1]: long-double reference phi(1) = $ref_phi ($ref_evals RHS evaluations)"
  echo
  echo "| method | steps (rejected) | RHS evals | Jacobians / LU | phi(1) rel. error | nutation amplitude on [1/2, 1] / exact | drift p_phi / p_psi / energy (relative) |"
  echo "|---|---:|---:|---:|---:|---:|---:|"
  exact=$(awk -v w=$w "$awk_lib"' BEGIN { printf "%.17g", exact_dtheta(w) }')
  for spec in "dop853 rtol 1e-10|method: dop853, rtol: 1e-10, atol: 1e-12" \
              "dop853 rtol 1e-13|method: dop853, rtol: 1e-13, atol: 1e-15" \
              "rosenbrock rtol 1e-6|method: rosenbrock, rtol: 1e-6, atol: 1e-8" \
              "rosenbrock rtol 1e-8|method: rosenbrock, rtol: 1e-8, atol: 1e-10" \
              "implicit_midpoint h 1e-3|method: implicit_midpoint, step: 1e-3" \
              "implicit_midpoint h 1e-4|method: implicit_midpoint, step: 1e-4" \
              "implicit_midpoint h 1e-5|method: implicit_midpoint, step: 1e-5" \
              "implicit_midpoint h 1e-6|method: implicit_midpoint, step: 1e-6"; do
    name=${spec%%|*}
    if ! run lagrangian $w 1 1001 "${spec#*|}" 2>/dev/null; then
      echo "| $name | fails: $(tail -1 "$work/summary" | cut -c1-60) | | | | | |"
      continue
    fi
    steps=$(field 's/.*steps   \([0-9]*\) accepted, \([0-9]*\) rejected.*/\1 (\2)/p')
    jac=$(field 's/.* \([0-9]*\) Jacobian evaluations, \([0-9]*\) factorisations.*/\1 \/ \2/p')
    acc=$(awk -F, -v ref=$ref_phi -v e=$exact 'NR == 3 { lo = 1; hi = 0 }
          NR > 2 && $1 >= 0.5 { if ($2 < lo) lo = $2; if ($2 > hi) hi = $2 }
          END { d = ($3 - ref)/ref; printf "%.1e | %.4f", d < 0 ? -d : d, (hi - lo)/e }' "$work/out.csv")
    echo "| $name | $steps | $(evals) | $jac | $acc | $(relative p_phi) / $(relative p_psi) / $(relative energy) |"
  done
  echo
done
echo "Lagrangian form, 1001 samples. phi(1) = Omega_p t - (Omega_p/omega_n) sin(omega_n t) + ...: a wrong nutation"
echo "phase alone moves phi(1) by up to I1/(I3 omega3) relative (2e-5 at 1e5, 2e-6 at 1e6). Nutation amplitude:"
echo "max - min of theta over the samples in [1/2, 1] (at random phases), over the exact delta_theta."
