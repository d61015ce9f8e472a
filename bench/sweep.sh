#!/usr/bin/env bash
# rotgen sweep — ensemble throughput, in one command (Markdown on stdout, progress on stderr):
#
#   bash bench/sweep.sh build/rotgen > bench/results/sweep.md
#
# The heavy top (models/heavy_top.yaml), 1024 members over initial theta 0.1 .. 1.5, t = 0 .. 10,
# 101 samples: members per second on one core for RK4 (step 0.01) and DOP853 (rtol 1e-8, atol
# 1e-10); DOP853 on 2 threads against 1; `mpirun -n 2` (one thread per rank) against one process,
# and the overhead per member that the ranks add. Each figure is the best of 3 runs of the members
# (the summary's "running the members" time: the kernels are compiled once, before, and cached).
# Timing claims live here, never in ctest.
set -euo pipefail
rotgen=$(realpath "${1:?usage: sweep.sh ROTGEN}")
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
members=1024
root_flag=()
[[ $(id -u) == 0 ]] && root_flag=(--allow-run-as-root)

scene() { # $1: name, $2: integrator mapping
  cat >"$work/$1.yaml" <<YAML
model: $root/models/heavy_top.yaml
initial: {theta: 0.5, psi_dot: 30}
time: {start: 0, end: 10, samples: 101}
integrator: $2
record: [theta, energy]
sweep:
  vary:
    initial.theta: {from: 0.1, to: 1.5, count: $members}
YAML
}
scene rk4 "{method: rk4, step: 0.01}"
scene dop853 "{method: dop853, rtol: 1e-8, atol: 1e-10}"

# seconds running the members: the best of 3 runs of "$@" (the sweep's own summary line)
best_of_3() {
  local best=""
  for _ in 1 2 3; do
    rm -rf "$work/out"
    local t
    t=$("$@" -o "$work/out" 2>&1 | sed -n 's/^  time    \([0-9.e+-]*\) s running the members.*/\1/p')
    [[ -n $t ]] || { echo "sweep.sh: no time from: $*" >&2; exit 1; }
    best=$(awk -v a="$t" -v b="$best" 'BEGIN { print (b == "" || a < b) ? a : b }')
  done
  echo "$best"
}
rate() { awk -v n=$members -v t="$1" 'BEGIN { printf "%.0f", n / t }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }

"$rotgen" sweep "$work/rk4.yaml" -o "$work/warm" -q -j 1 # compile the kernels into the cache
echo "rk4, 1 thread" >&2
rk4_1=$(best_of_3 "$rotgen" sweep "$work/rk4.yaml" -j 1)
echo "dop853, 1 thread" >&2
dop_1=$(best_of_3 "$rotgen" sweep "$work/dop853.yaml" -j 1)
echo "dop853, 2 threads" >&2
dop_2=$(best_of_3 "$rotgen" sweep "$work/dop853.yaml" -j 2)
echo "dop853, mpirun -n 2" >&2
mpi_2=$(best_of_3 mpirun -n 2 --oversubscribe "${root_flag[@]}" "$rotgen" sweep "$work/dop853.yaml")
# overhead per member: the core-seconds two ranks spend beyond one process's, per member
overhead=$(awk -v n=$members -v one="$dop_1" -v two="$mpi_2" \
  'BEGIN { printf "%.1f", (2 * two - one) / n * 1e6 }')

cat <<EOF2
# rotgen sweep: ensemble throughput

\`bash bench/sweep.sh build/rotgen > bench/results/sweep.md\`; $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')),
load average $(cut -d' ' -f1-3 /proc/loadavg) when it finished (the machine is shared: the
figures are the best of 3 runs and still move with the load).

The heavy top, $members members (initial theta 0.1 .. 1.5), t = 0 .. 10, 101 samples, records theta and
energy; the time is the sweep's own "running the members" (the kernels compiled once, before).

| run | seconds | members/s | per member | speed-up |
|---|---:|---:|---:|---:|
| RK4, step 0.01, 1 thread | $rk4_1 | $(rate "$rk4_1") | $(awk -v t="$rk4_1" -v n=$members 'BEGIN { printf "%.0f µs", t / n * 1e6 }') | |
| DOP853, rtol 1e-8, 1 thread | $dop_1 | $(rate "$dop_1") | $(awk -v t="$dop_1" -v n=$members 'BEGIN { printf "%.0f µs", t / n * 1e6 }') | 1 |
| DOP853, 2 threads (\`-j 2\`) | $dop_2 | $(rate "$dop_2") | | $(ratio "$dop_1" "$dop_2") (goal 1.8) |
| DOP853, \`mpirun -n 2\` | $mpi_2 | $(rate "$mpi_2") | | $(ratio "$dop_1" "$mpi_2") (goal 1.7) |

MPI overhead per member (2 x the 2-rank time - the 1-process time, over $members members): $overhead µs of
core time.
EOF2
