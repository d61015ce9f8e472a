#!/usr/bin/env bash
# Splitting on the exact free flow (split2/4/6) against DOP853 at fast spin: writes
# bench/results/split.md (issue 17). One command, from anywhere:
#   bench/split/split.sh [--tabulate]      (--tabulate: the tables from bench/results/split_runs.txt)
# Builds bench/split/split_bench.cpp with g++ -O2 against the runtime headers (Eigen, Boost.Math),
# runs it (about 5 minutes: the long-double references at spin 1e4 dominate), and tabulates its
# output with awk: per body and spin, the cheapest run of each method that reaches an attitude
# error of 1e-6 and of 1e-9 at t = 10, and the speed ratio of the best split method to DOP853.
# Both sides run under error control at rtol = atol = 1e-4 .. 1e-13 (the split methods by step
# doubling, runtime/steppers/split_doubling.hpp), both calibrated as `rotgen simulate` runs them
# (bench/split/calibrated.hpp).
set -euo pipefail
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ "${1:-}" = --tabulate ]; then # the tables again from the committed runs, not run anew
  cp bench/results/split_runs.txt "$work/runs.txt"
else
  g++ -O2 -std=c++17 -I runtime -I /usr/include/eigen3 bench/split/split_bench.cpp -o "$work/bench"
  "$work/bench" > "$work/runs.txt"
fi
out=bench/results/split.md
{
  cat <<'MD'
# Splitting on the exact free flow against DOP853 at fast spin

`bench/split/split.sh` (bench/split/split_bench.cpp). Heavy top, M g h = 0.981, centre of mass on
the body z axis, the symmetric body I = (1, 1, 0.5) and the asymmetric I = (1, 1.2, 0.5), tilted 0.5 rad, released with phi_dot = theta_dot = 0 and psi_dot = spin; t = 0..10.
Error: the angle between the attitude at t = 10 and a long-double DOP853 run at rtol 1e-17. Cost: the
wall time of one run (median of 5), the cheapest run of the method that meets the error target
(DOP853 at rtol = atol = 1e-4 .. 1e-13 on the body form, quaternion and omega; split2/4/6 under
error control, step doubling, at the same rtol = atol; both calibrated as `rotgen simulate` runs
them, so that rtol means the error at the samples; a method's cost at a target is that of its
cheapest run from which every tighter rtol also meets it). "best split" is the cheapest of split2,
split4, split6; the ratio is DOP853's time over
it (> 1: the split method is faster). A dash: no run met the target. The machine is shared (2 cores,
other builds running): single timings scatter by up to 2x; the raw runs are in split_runs.txt.

MD
  awk -f bench/split/tabulate.awk "$work/runs.txt"
  echo
  echo "Machine: $(nproc) cores, $(uname -m); $(g++ --version | head -1); $(date -u +%Y-%m-%d)."
} > "$out.tmp"
mv "$out.tmp" "$out"
cp "$work/runs.txt" bench/results/split_runs.txt
echo "wrote $out"
