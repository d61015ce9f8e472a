#!/usr/bin/env bash
# rotgen sweep — ensemble throughput, in one command (Markdown on stdout, progress on stderr):
#
#   bash bench/sweep.sh build/rotgen > bench/results/sweep.md
#
# The heavy top (models/heavy_top.yaml), 1024 members over initial theta 0.1 .. 1.5, t = 0 .. 10,
# 101 samples: members per second on one core for RK4 (step 0.01) and DOP853 (rtol 1e-8, atol
# 1e-10), one member at a time and in SIMD lanes (`--lanes 8`, the runs interleaved); the cost of a
# member outside its integration (the same sweep to t = 0.01); DOP853 on 2 threads against 1;
# `mpirun -n 2` (one thread per rank) against one process, and what the ranks cost in CPU, once
# and per member (from this sweep and one of 4 times the members). Each figure is the median of 9
# runs of the members (the summary's "running the members" time: the kernels are compiled once,
# before, and cached), the ways of running a scene interleaved (one of each in turn), each round
# from fresh copies of rotgen and the kernel cache (a copy's speed depends on where its pages lie
# in memory on a virtual machine: docs/design-notes.md).
# Timing claims live here, never in ctest.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/summary_time.sh"
source "$(dirname "${BASH_SOURCE[0]}")/heavy_top_sweep.sh"
rotgen=$(realpath "${1:?usage: sweep.sh ROTGEN}")
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export ROTGEN_CACHE_DIR=$work/cache # its own kernel cache: the libraries timed below are these
members=1024
root_flag=()
[[ $(id -u) == 0 ]] && root_flag=(--allow-run-as-root)

scene() { # $1: name, $2: integrator mapping
  heavy_top_sweep "$work/$1.yaml" "$members" "$2"
}
scene rk4 "{method: rk4, step: 0.01}"
scene dop853 "{method: dop853, rtol: 1e-8, atol: 1e-10}"
sed 's/end: 10,/end: 0.01,/' "$work/rk4.yaml" >"$work/short.yaml"
# four times the members: what MPI costs per member, apart from what it costs once
sed "s/count: $members}/count: $((4 * members))}/" "$work/dop853.yaml" >"$work/dop853_4x.yaml"
lanes=8

# "WALL CPU" of one run of "$@": WALL the sweep's own "running the members" seconds, CPU the
# user + system seconds of the whole command (every rank, preparation included) from /usr/bin/time
one_run() {
  rm -rf "$work/out"
  local t cpu
  # the summary (standard output): "time    <number> <s|ms|us> running the members", in seconds
  t=$(/usr/bin/time -f "cpu %U %S" -o "$work/cpu" "$@" -o "$work/out" |
      summary_seconds "running the members")
  [[ -n $t ]] || { echo "sweep.sh: no time from: $*" >&2; exit 1; }
  cpu=$(awk '/^cpu/ { print $2 + $3 }' "$work/cpu")
  echo "$t $cpu"
}
# Fresh copies of rotgen and of the kernel cache for a round (new pages), which run_as runs
fresh_copies() {
  rm -rf "$work/round" && mkdir -p "$work/round"
  cp "$rotgen" "$work/round/rotgen" && cp -r "$ROTGEN_CACHE_DIR" "$work/round/cache"
}
# One run of the scene $1 as $2 says, from the round's copies: one (1 thread), lanes (1 thread,
# --lanes), two (2 threads) or mpi (2 ranks of 1 thread); "WALL CPU" as one_run gives them
run_as() {
  local bin=$work/round/rotgen
  case $2 in
    one) ROTGEN_CACHE_DIR=$work/round/cache one_run "$bin" sweep "$1" -j 1 ;;
    lanes) ROTGEN_CACHE_DIR=$work/round/cache one_run "$bin" sweep "$1" -j 1 --lanes $lanes ;;
    two) ROTGEN_CACHE_DIR=$work/round/cache one_run "$bin" sweep "$1" -j 2 ;;
    mpi) ROTGEN_CACHE_DIR=$work/round/cache one_run mpirun -n 2 --oversubscribe "${root_flag[@]}" \
           -x ROTGEN_CACHE_DIR "$bin" sweep -j 1 "$1" ;;
  esac
}
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
# "WALL CPU" for each way $2 $3 ... of running the scene $1, the medians of 9 of each (wall and CPU
# apart), the runs interleaved (one of each in turn, from a round's fresh copies) so that all see
# the same load
median_of_9_each() {
  local scene=$1 k t cpu
  shift
  rm -f "$work"/way-*
  for _ in 1 2 3 4 5 6 7 8 9; do
    fresh_copies
    k=0
    for way in "$@"; do
      run_as "$scene" "$way" >>"$work/way-$k"
      k=$((k + 1))
    done
  done
  for ((k = 0; k < $#; k++)); do
    printf '%s %s ' "$(awk '{ print $1 }' "$work/way-$k" | median)" \
      "$(awk '{ print $2 }' "$work/way-$k" | median)"
  done
  echo
}
rate() { awk -v n=$members -v t="$1" 'BEGIN { printf "%.0f", n / t }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
us() { awk -v t="$1" -v n=$members 'BEGIN { printf "%.0f", t / n * 1e6 }'; }
sub_us() { awk -v a="$1" -v b="$2" -v n=$members 'BEGIN { printf "%.0f", (a - b) / n * 1e6 }'; }
ratio_sub() { awk -v a="$1" -v b="$2" -v c="$3" -v d="$4" 'BEGIN { printf "%.2f", (a - b) / (c - d) }'; }

"$rotgen" sweep "$work/rk4.yaml" -o "$work/warm" -q -j 1 # compile the kernels into the cache
"$rotgen" sweep "$work/dop853.yaml" -o "$work/warm" -q -j 1
"$rotgen" sweep "$work/rk4.yaml" -o "$work/warm" -q -j 1 --lanes $lanes # the batch kernel
echo "rk4, 1 thread, without and with --lanes $lanes" >&2
read -r rk4_1 rk4_1c rk4_l rk4_lc < <(median_of_9_each "$work/rk4.yaml" one lanes)
echo "rk4 to t = 0.01, 1 thread, without and with --lanes $lanes" >&2
read -r short_1 short_1c short_l short_lc < <(median_of_9_each "$work/short.yaml" one lanes)
arch=$("$rotgen" sweep "$work/rk4.yaml" -o "$work/out" -j 1 --lanes $lanes |
       sed -n 's/^  lanes .* in batches of [0-9]* (\(.*\))$/\1/p')
echo "dop853: 1 thread, --lanes $lanes, 2 threads, mpirun -n 2" >&2
read -r dop_1 dop_1c dop_l dop_lc dop_2 dop_2c mpi_2 mpi_2c < <(median_of_9_each "$work/dop853.yaml" \
  one lanes two mpi)
# one member's right-hand side: the scalar kernel against the batch kernel (bench/lanes/rhs_time.cpp),
# the medians over 5 fresh copies of the two libraries
"${CXX:-g++}" -O2 "$root/bench/lanes/rhs_time.cpp" -o "$work/rhs_time" -ldl
for _ in 1 2 3 4 5; do
  cp "$(ls "$ROTGEN_CACHE_DIR"/heavy_top-*.so | head -1)" "$work/scalar.so"
  cp "$(ls "$ROTGEN_CACHE_DIR"/heavy_top_lanes-*.so | head -1)" "$work/batch.so"
  "$work/rhs_time" "$work/scalar.so" "$work/batch.so" 6 5 >>"$work/rhs_times"
done
read -r rhs_1 rhs_4 rhs_8 <<<"$(for c in 1 2 3; do awk -v c=$c '{ print $c }' "$work/rhs_times" | median; done | tr '\n' ' ')"
echo "dop853 with $((4 * members)) members: 1 thread, mpirun -n 2" >&2
read -r _ big_1c _ big_2c < <(median_of_9_each "$work/dop853_4x.yaml" one mpi)
# MPI's CPU cost, the 2-rank CPU time minus the 1-process CPU time, is a + b·members: b from the
# two sizes, per member; a, once per sweep
mpi_per_member=$(awk -v n=$members -v a="$dop_1c" -v b="$mpi_2c" -v c="$big_1c" -v d="$big_2c" \
  'BEGIN { printf "%.0f", ((d - c) - (b - a)) / (3 * n) * 1e6 }')
mpi_once=$(awk -v n=$members -v a="$dop_1c" -v b="$mpi_2c" -v c="$big_1c" -v d="$big_2c" \
  'BEGIN { printf "%.2f", (b - a) - ((d - c) - (b - a)) / 3 }')

cat <<EOF2
# rotgen sweep: ensemble throughput

\`bash bench/sweep.sh build/rotgen > bench/results/sweep.md\`; $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')),
load average $(cut -d' ' -f1-3 /proc/loadavg) when it finished (the machine is shared: the
figures are medians of 9 runs, interleaved, each round from fresh copies of rotgen and its
kernels, and still move with the load).

The heavy top, $members members (initial theta 0.1 .. 1.5), t = 0 .. 10, 101 samples, records theta and
energy; the time is the sweep's own "running the members" (the kernels compiled once, before).

| run | wall s | members/s (wall) | wall speed-up | CPU µs per member |
|---|---:|---:|---:|---:|
| RK4, step 0.01, 1 thread | $rk4_1 | $(rate "$rk4_1") | 1 | $(us "$rk4_1c") |
| RK4, step 0.01, 1 thread, \`--lanes $lanes\` | $rk4_l | $(rate "$rk4_l") | $(ratio "$rk4_1" "$rk4_l") (goal 2.5) | $(us "$rk4_lc") |
| RK4 to t = 0.01 (a member's cost outside its integration), 1 thread | $short_1 | $(rate "$short_1") | | $(us "$short_1c") |
| the same, \`--lanes $lanes\` | $short_l | $(rate "$short_l") | $(ratio "$short_1" "$short_l") | $(us "$short_lc") |
| DOP853, rtol 1e-8, 1 thread | $dop_1 | $(rate "$dop_1") | 1 | $(us "$dop_1c") |
| DOP853, rtol 1e-8, 1 thread, \`--lanes $lanes\` | $dop_l | $(rate "$dop_l") | $(ratio "$dop_1" "$dop_l") (goal 1.5) | $(us "$dop_lc") |
| DOP853, 2 threads (\`-j 2\`) | $dop_2 | $(rate "$dop_2") | $(ratio "$dop_1" "$dop_2") (goal 1.8) | $(us "$dop_2c") |
| DOP853, \`mpirun -n 2\` | $mpi_2 | $(rate "$mpi_2") | $(ratio "$dop_1" "$mpi_2") (goal 1.7) | $(us "$mpi_2c") |

Lanes: \`--lanes $lanes\` runs $lanes neighbouring members together, the right-hand side compiled for
$arch; the scalar and lane runs were interleaved. Integration alone (the run minus the run to
t = 0.01, in wall µs per member): RK4 $(sub_us "$rk4_1" "$short_1") scalar, $(sub_us "$rk4_l" "$short_l") in lanes ($(ratio_sub "$rk4_1" "$short_1" "$rk4_l" "$short_l")×); DOP853
$(sub_us "$dop_1" "$short_1") scalar, $(sub_us "$dop_l" "$short_l") in lanes ($(ratio_sub "$dop_1" "$short_1" "$dop_l" "$short_l")×).

One member's right-hand side (\`bench/lanes/rhs_time.cpp\`, calls interleaved, best of 5, the median over 5 fresh copies of the kernels): $rhs_1 ns
scalar, $rhs_4 ns in a batch of 4 lanes ($(ratio "$rhs_1" "$rhs_4")×), $rhs_8 ns in a batch of 8
($(ratio "$rhs_1" "$rhs_8")×: two vectors per call keep more arithmetic in flight).

CPU µs per member: the command's user + system time (all ranks, preparation included) over the
$members members. What two ranks cost in CPU beyond one process, from this sweep and the same
with $((4 * members)) members (DOP853, medians of 9 each, interleaved): $mpi_once s once per sweep
(\`mpirun\`'s and MPI's start-up, the second rank's preparation) and $mpi_per_member µs per member
(the queue's messages; within the noise of the timings when near 0).
EOF2
