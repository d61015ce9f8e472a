#!/usr/bin/env bash
# rotgen sweep — resident memory of a large sweep with trajectories (Markdown on stdout):
#
#   bash bench/sweep_memory.sh build/rotgen [MEMBERS:END...] > bench/results/sweep_memory.md
#
# The heavy top (models/heavy_top.yaml), MEMBERS members over initial theta 0.1 .. 1.5, t = 0 ..
# END, 101 samples, DOP853 (rtol 1e-8, atol 1e-10), two recorded quantities (theta, energy), with
# --trajectories: members x 101 x 3 x 8 bytes of samples (2.4 GB for 1e6), whatever END. Default:
# 1000000:0.1 (short runs: the same files, in less time) and 100000:10. The maximum resident set
# size is /usr/bin/time's %M; the time is the sweep's "running the members". Each size runs only
# if the file system has twice the estimate free; its output is removed after.
set -euo pipefail
rotgen=$(realpath "${1:?usage: sweep_memory.sh ROTGEN [MEMBERS...]}")
shift
sizes=("$@")
((${#sizes[@]})) || sizes=(1000000:0.1 100000:10)
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene() { # scene END
  cat >"$work/scene.yaml" <<YAML
model: $root/models/heavy_top.yaml
initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}
time: {start: 0, end: $1, samples: 101}
integrator: {method: dop853, rtol: 1e-8, atol: 1e-10}
record: [theta, energy]
YAML
}
scene 10
"$rotgen" sweep "$work/scene.yaml" -o "$work/warm" --vary initial.theta=0.1:1.5:2 -q # compile once

echo "# rotgen sweep: resident memory with --trajectories"
echo
echo "\`bash bench/sweep_memory.sh build/rotgen ${sizes[*]}\` on $(nproc) cores ($(date -u +%Y-%m-%d))."
echo "The heavy top, t = 0 .. END, 101 samples, DOP853 rtol 1e-8, record [theta, energy]; every"
echo "member's samples in trajectories.h5. Max RSS: /usr/bin/time -f %M."
echo
echo "| members | END | trajectories.h5 | summary.csv | max RSS | running the members |"
echo "|---:|---:|---:|---:|---:|---:|"
for size in "${sizes[@]}"; do
  n=${size%%:*} end=${size#*:}
  scene "$end"
  need=$((n * 101 * 3 * 8 * 2))
  free=$(($(df -Pk "$work" | awk 'NR == 2 {print $4}') * 1024))
  if ((free < need)); then
    echo "| $n | $end | (skipped: $((free / 1000000)) MB free, $((need / 1000000)) MB needed) | | | |"
    continue
  fi
  echo "sweep of $n members ..." >&2
  /usr/bin/time -f %M -o "$work/rss" "$rotgen" sweep "$work/scene.yaml" -o "$work/out" \
    --trajectories --vary "initial.theta=0.1:1.5:$n" >"$work/err" 2>&1
  rss=$(tail -1 "$work/rss")
  h5=$(stat -c %s "$work/out/trajectories.h5")
  csv=$(stat -c %s "$work/out/summary.csv")
  t=$(sed -n 's/^  time    \(.*\) running the members.*/\1/p' "$work/err")
  awk -v n="$n" -v end="$end" -v h5="$h5" -v csv="$csv" -v rss="$rss" -v t="$t" \
    'BEGIN {printf "| %d | %s | %.2f GB | %.0f MB | %d MB | %s |\n", n, end, h5 / 1e9, csv / 1e6, rss / 1024, t}' 
  rm -rf "$work/out"
done
