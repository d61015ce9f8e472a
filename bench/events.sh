#!/usr/bin/env bash
# The cost of events (scene `events:`, runtime/integrate/events.hpp): `rotgen simulate` of the
# shipped heavy top (models/scenes/heavy_top_nutation.yaml: Lagrangian form, dop853 rtol 1e-10
# atol 1e-12) over a longer span, t in [0, 2000] (~86,000 steps, 1001 samples), without events,
# with one event that never fires (theta - 3: theta stays in [0.5, 0.52]) and with one that fires
# once per nutation period (theta_dot, falling: at each maximum of theta).
#   bench/events.sh [path/to/rotgen] [repeats] > bench/results/events.md
# Each variant runs `repeats` times (default 11), interleaved; the time is the integration's own
# wall time (the summary's "integrating" time: stepping, sampling, events; no derivation or compiling,
# the kernels come from the cache after the first run); the table gives the medians and the ratios,
# and the ratios of each variant's fastest run (a 2-core VM here runs at two speeds from run to run)
# to the run without events.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
rotgen=$(realpath "${1:-build/rotgen}")
repeats=${2:-11}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

variants=("none" "never fires" "fires every period")
events=("" "events: [{name: high, when: theta - 3}]"
        "events: [{name: turn, when: theta_dot, direction: falling}]")
for i in 0 1 2; do
  cat > "$work/scene$i.yaml" <<YAML
model: $root/models/heavy_top.yaml
form: lagrangian
initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}
time: {start: 0, end: 2000, samples: 1001}
integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}
record: [theta, phi, phi_dot, theta_dot, energy, p_phi, p_psi]
${events[$i]}
YAML
  (cd "$work" && "$rotgen" simulate "scene$i.yaml" -o "out$i.csv" -q) # compile once
done
# The summary's "time    <number> <s|ms|us> <what>" (a unit that fits the duration), in ms.
in_ms() {
  sed -n "s/^  time    \([0-9.]*\) \(s\|ms\|us\) $1.*/\1 \2/p" |
    awk '{ print $1 * ($2 == "s" ? 1e3 : $2 == "ms" ? 1 : 1e-3) }'
}
for ((r = 0; r < repeats; r++)); do
  for i in 0 1 2; do
    (cd "$work" && "$rotgen" simulate "scene$i.yaml" -o "out$i.csv") | in_ms integrating \
      >> "$work/times$i"
  done
done
median() { sort -g "$1" | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
base=$(median "$work/times0")
best0=$(sort -g "$work/times0" | head -1)
echo "| events | median integrate time (ms) | min .. max (ms) | ratio to none | ratio of the fastest runs | events found | RHS evaluations |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for i in 0 1 2; do
  m=$(median "$work/times$i")
  best=$(sort -g "$work/times$i" | head -1)
  range=$(sort -g "$work/times$i" | sed -n '1p;$p' | paste -sd' ' | awk '{ printf "%s .. %s", $1, $2 }')
  summary=$(cd "$work" && "$rotgen" simulate "scene$i.yaml" -o "out$i.csv")
  found=$(echo "$summary" | sed -n 's/.*event   [a-z]*: \([0-9]*\) time.*/\1/p')
  evals=$(echo "$summary" | sed -n 's/.*; \([0-9]*\) RHS.*/\1/p')
  echo "| ${variants[$i]} | $m | $range | $(awk -v a="$m" -v b="$base" 'BEGIN { printf "%.3f", a / b }') | $(awk -v a="$best" -v b="$best0" 'BEGIN { printf "%.3f", a / b }') | ${found:-0} | $evals |"
done
echo
echo "heavy top (heavy_top_nutation.yaml's state), t in [0, 2000], dop853 rtol 1e-10 atol 1e-12,"
echo "1001 samples; medians of $repeats runs each, interleaved; $(nproc) cores, load $(cut -d' ' -f1 /proc/loadavg)."
echo "\"ratio of the fastest runs\": the fastest run of each variant over the fastest without events"
echo "(steadier than the medians where the machine's speed changes from run to run)."
