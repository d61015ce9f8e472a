#!/usr/bin/env bash
# The split methods under error control on the goal grid of issue 25 §1: writes
# bench/results/split_control.md. One command, from anywhere:
#   bench/split/control.sh
# Builds bench/split/control_bench.cpp with g++ -O2 against the runtime headers (Eigen, Boost.Math)
# and runs it (about 10 minutes on a loaded 2-core machine: DOP853 at spin 1e4 dominates).
set -euo pipefail
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
g++ -O2 -std=c++17 -I runtime -I /usr/include/eigen3 bench/split/control_bench.cpp -o "$work/bench"
"$work/bench" > "$work/runs.txt"
"$work/bench" floor > "$work/floor.txt"
"$work/bench" unbounded > "$work/unbounded.txt"
out=bench/results/split_control.md
{
  cat <<'MD'
# The split methods under error control: rtol against the error at t = 10

`bench/split/control.sh` (bench/split/control_bench.cpp). Heavy top, M g h = 0.981, centre of mass
on the body z axis, released at theta0 with phi_dot = theta_dot = 0 and psi_dot = spin; t = 0..10.
split2/4/6 given rtol = atol (steps under error control: step doubling,
runtime/steppers/split_doubling.hpp) and DOP853 at the same rtol = atol, both calibrated as
`rotgen simulate` calibrates a run of the body form (rtol means the error at the samples;
bench/split/calibrated.hpp). Error: max |dq_i| of
q0..q3 at t = 10 against DOP853 at rtol = atol = 1e-13 (whose own error is about 2e-9 at spin 1e4:
the floor of the split columns there). Bound: max(10 rtol, 2 x DOP853's error). Each cell:
split error / rtol, then DOP853's error / rtol; steps: the split run's accepted and rejected steps
(each step is three compositions: one of h and two of h/2).

| body | theta0 | spin | method | rtol | split error | split / rtol | DOP853 / rtol | steps | meets bound |
|---|---|---|---|---|---|---|---|---|---|
MD
  awk '{ printf "| %s | %s | %s | %s | %s | %s | %.3g | %.3g | %s | %s |\n", $1, $2, $3, $4, $5, $6, $6 / $5, $7 / $5, $8, $11 }' "$work/runs.txt"
  echo
  awk '{ n++; if ($11 == "yes") ok++; r = $6 / $5; if (r > worst) { worst = r; w = $0 } }
       END { printf "%d of %d runs meet the bound; the largest split error / rtol: %.3g (%s).\n", ok, n, worst, w }' "$work/runs.txt"
  awk '$3 <= 1000 { r = $6 / $5; if (r > worst) { worst = r; w = $0 } }
       END { printf "At spins up to 1000 the largest split error / rtol is %.3g (%s).\n", worst, w }' "$work/runs.txt"
  awk '$3 <= 1000 && $5 <= 1e-6 { r = $6 / $5; if (r > worst) { worst = r; w = $0 } }
       END { printf "At spins up to 1000 and rtol up to 1e-6 it is %.3g (%s).\n", worst, w }' "$work/runs.txt"
  awk '$11 != "yes" { printf "Misses the bound: %s\n", $0 }' "$work/runs.txt"
  echo
  echo "The reference's own error at spin 1e4 (symmetric body, theta0 = 0.3; max |dq_i| at t = 10):"
  echo "$(cat "$work/floor.txt"): the split columns there (about 2e-9 at every rtol) are the"
  echo "reference's error, and those cells meet the bound by its second term."
  echo
  echo "Without the bound on a step's turning (max_turns = 0, split_doubling.hpp), split2 at spin 1000 and"
  echo "rtol 1e-4 takes steps of tens of turns, where the doubling estimate aliases with the spin:"
  echo
  sed 's/^/    /' "$work/unbounded.txt"
  echo
  echo "Machine: $(nproc) cores, $(uname -m); $(g++ --version | head -1); $(date -u +%Y-%m-%d)."
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
