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
initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}
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

# "WALL CPU" of the best of 3 runs of "$@" (by wall time): WALL the sweep's own "running the
# members" seconds, CPU the user + system seconds of the whole command (every rank, preparation
# included) from /usr/bin/time
best_of_3() {
  local best="" best_cpu=""
  for _ in 1 2 3; do
    rm -rf "$work/out"
    local t cpu
    t=$(/usr/bin/time -f "cpu %U %S" -o "$work/cpu" "$@" -o "$work/out" 2>&1 |
        sed -n 's/^  time    \([0-9.e+-]*\) s running the members.*/\1/p')
    [[ -n $t ]] || { echo "sweep.sh: no time from: $*" >&2; exit 1; }
    cpu=$(awk '/^cpu/ { print $2 + $3 }' "$work/cpu")
    if [[ -z $best ]] || awk -v a="$t" -v b="$best" 'BEGIN { exit !(a < b) }'; then
      best=$t best_cpu=$cpu
    fi
  done
  echo "$best $best_cpu"
}
rate() { awk -v n=$members -v t="$1" 'BEGIN { printf "%.0f", n / t }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
us() { awk -v t="$1" -v n=$members 'BEGIN { printf "%.0f", t / n * 1e6 }'; }

"$rotgen" sweep "$work/rk4.yaml" -o "$work/warm" -q -j 1 # compile the kernels into the cache
"$rotgen" sweep "$work/dop853.yaml" -o "$work/warm" -q -j 1
echo "rk4, 1 thread" >&2
read -r rk4_1 rk4_1c < <(best_of_3 "$rotgen" sweep "$work/rk4.yaml" -j 1)
echo "dop853, 1 thread" >&2
read -r dop_1 dop_1c < <(best_of_3 "$rotgen" sweep "$work/dop853.yaml" -j 1)
echo "dop853, 2 threads" >&2
read -r dop_2 dop_2c < <(best_of_3 "$rotgen" sweep "$work/dop853.yaml" -j 2)
echo "dop853, mpirun -n 2" >&2
read -r mpi_2 mpi_2c < <(best_of_3 mpirun -n 2 --oversubscribe "${root_flag[@]}" "$rotgen" sweep -j 1 \
  "$work/dop853.yaml")
# overhead per member: the core time two ranks spend beyond one process's, per member
overhead=$(awk -v n=$members -v one="$dop_1c" -v two="$mpi_2c" \
  'BEGIN { printf "%.0f", (two - one) / n * 1e6 }')

cat <<EOF2
# rotgen sweep: ensemble throughput

\`bash bench/sweep.sh build/rotgen > bench/results/sweep.md\`; $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')),
load average $(cut -d' ' -f1-3 /proc/loadavg) when it finished (the machine is shared: the
figures are the best of 3 runs and still move with the load).

The heavy top, $members members (initial theta 0.1 .. 1.5), t = 0 .. 10, 101 samples, records theta and
energy; the time is the sweep's own "running the members" (the kernels compiled once, before).

| run | wall s | members/s (wall) | wall speed-up | CPU µs per member |
|---|---:|---:|---:|---:|
| RK4, step 0.01, 1 thread | $rk4_1 | $(rate "$rk4_1") | | $(us "$rk4_1c") |
| DOP853, rtol 1e-8, 1 thread | $dop_1 | $(rate "$dop_1") | 1 | $(us "$dop_1c") |
| DOP853, 2 threads (\`-j 2\`) | $dop_2 | $(rate "$dop_2") | $(ratio "$dop_1" "$dop_2") (goal 1.8) | $(us "$dop_2c") |
| DOP853, \`mpirun -n 2\` | $mpi_2 | $(rate "$mpi_2") | $(ratio "$dop_1" "$mpi_2") (goal 1.7) | $(us "$mpi_2c") |

CPU µs per member: the command's user + system time (all ranks, preparation included) over the
$members members. MPI overhead per member (the 2-rank CPU time minus the 1-process CPU time, over
the members): $overhead µs (rank 0's queue, the messages, the second rank's preparation).
EOF2
