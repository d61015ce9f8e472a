#!/usr/bin/env bash
# Nearly equal moments and extreme ratios: does rotgen's generated code lose more accuracy than the
# problem forces?
#   bench/extremes/moments.sh [path/to/rotgen]
#
# Table 1, nearly equal moments: the free asymmetric top with I = (1.3, 1.3 (1 + eps), 2.1) (the
# double nearest to 1.3 (1 + eps), printed with 17 digits so that rotgen and the reference read the
# same number), omega(0) = (1, 0.1, 0.5), over t in [0, 100] (1001 samples), dop853 rtol 1e-12
# atol 1e-14, in the body form (y = omega) and the Lagrangian and Hamiltonian forms (initial angles
# put the space z axis along L, so theta stays near 0.89, far from gimbal lock). Columns:
#   swing     max |omega3(t) - omega3(0)| of the exact solution: the motion that exists only
#             because I1 != I2 (it shrinks like eps);
#   floor     the largest change of the exact omega(t) when one input (a moment or a component of
#             omega(0)) moves by its rounding to double (free_top_error --floor): what the data
#             force on any double-precision computation;
#   error     max |omega - reference| over the samples: the Jacobi-elliptic solution in long
#             double for the same double inputs, and a long-double dop853 run (rtol 3e-18) of the
#             checked-in body-form kernels (free_top_error.cpp), printed "exact / run";
#   kernel    the largest error of the generated right-hand side at 10,000 random states, in
#             units of the bound the rounding of the inputs forces (rhs_rounding.cpp): against
#             moments and state rounded (data) / against the state rounded, the moments exact.
# Table 2, extreme ratios: the same in the body form (the Euler-angle forms need a chart per
# trajectory; their kernels are measured in the last column), omega(0) = (1, 0.1, 0.5).
source "$(dirname "$0")/common.sh" "$@"
flags=(-O2 -std=c++17 -I generated -I runtime -I /usr/include/eigen3)
g++ "${flags[@]}" bench/extremes/free_top_error.cpp -o "$work/free_top_error"
g++ "${flags[@]}" bench/extremes/rhs_rounding.cpp -o "$work/rhs_rounding"

w="1 0.1 0.5"
# run FORM I1 I2 I3 -> "error-vs-exact error-vs-long-double-run swing-of-omega3" for omega(0) = $w
run() {
  local angles
  angles=$(awk -v a=$2 -v b=$3 -v c=$4 'BEGIN { L1 = a; L2 = b*0.1; L3 = c*0.5; L = sqrt(L1*L1 + L2*L2 + L3*L3)
           printf "phi: 0, theta: %.17g, psi: %.17g", atan2(sqrt(L1*L1 + L2*L2), L3), atan2(L1, L2) }')
  cat > "$work/scene.yaml" <<YAML
model: {name: free_top, parameters: {I1: 1, I2: 2, I3: 3}, inertia: [I1, I2, I3]}
parameters: {I1: $2, I2: $3, I3: $4}
form: $1
initial: {$angles, omega1: 1, omega2: 0.1, omega3: 0.5}
time: {end: 100, samples: 1001}
integrator: {method: dop853, rtol: 1e-12, atol: 1e-14}
record: [omega1, omega2, omega3]
YAML
  if (cd "$work" && "$rotgen" simulate scene.yaml -o out.csv > summary 2>&1); then
    "$work/free_top_error" $2 $3 $4 $w "$work/out.csv"
  else
    echo "fails - -"
    tail -1 "$work/summary" >&2
  fi
}
kernel() { # I1 I2 I3 -> "body l / h" cells
  read -r bd bs ld ls hd hs < <("$work/rhs_rounding" "$@")
  echo "$bd / $bs | $ld / $ls | $hd / $hs"
}

echo "| eps | I2 | swing of omega3 | floor (data rounding) | error (exact / run), body form | Lagrangian | Hamiltonian | kernel (data / state bound): body | Lagrangian | Hamiltonian |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for eps in 1e-2 1e-4 1e-6 1e-8 1e-10 1e-12 1e-14; do
  I2=$(awk -v e=$eps 'BEGIN { printf "%.17g", 1.3*(1 + e) }')
  read -r be br swing < <(run body 1.3 $I2 2.1)
  read -r le lr _ < <(run lagrangian 1.3 $I2 2.1)
  read -r he hr _ < <(run hamiltonian 1.3 $I2 2.1)
  floor=$("$work/free_top_error" --floor 1.3 $I2 2.1 $w 100 1000)
  echo "| $eps | $I2 | $swing | $floor | $be / $br | $le / $lr | $he / $hr | $(kernel 1.3 $I2 2.1) |"
done
echo
echo "I = (1.3, I2, 2.1), omega(0) = (${w// /, }), t in [0, 100]; dop853 rtol 1e-12 atol 1e-14"
echo
echo "| moments | largest / smallest | floor (data rounding) | error (exact / run), body form | kernel (data / state bound): body | Lagrangian | Hamiltonian |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for I in "1 1.5 2" "1e-6 1.5e-6 2e-6" "1e6 1.5e6 2e6" "1 1.001 2" "1 1e6 1000000.5" "1e-6 1 1.0000005" \
         "1e-6 1e6 1000000.0000005"; do
  set -- $I
  ratio=$(awk -v a=$1 -v c=$3 'BEGIN { printf "%.0e", c/a }')
  floor=$("$work/free_top_error" --floor $I $w 100 1000)
  read -r be br _ < <(run body $I)
  echo "| ($1, $2, $3) | $ratio | $floor | $be / $br | $(kernel $I) |"
done
echo
echo "omega(0) = (${w// /, }), t in [0, 100]; dop853 rtol 1e-12 atol 1e-14"
