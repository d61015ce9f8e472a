#!/usr/bin/env bash
# rotgen sweep — how the members' time scales with the cores this machine has, as threads, as MPI
# ranks and as both (Markdown on stdout, progress on stderr):
#
#   bash bench/sweep_scaling.sh build/rotgen [MEMBERS] > bench/results/sweep_scaling.md
#
# The heavy top (models/heavy_top.yaml), MEMBERS (default 16,384) members over initial theta
# 0.1 .. 1.5, t = 0 .. 10, DOP853 rtol 1e-8, the summary's "running the members" time. For each
# power of two k up to the cores (nproc): k threads, k ranks of one thread, and above 2 cores 2
# ranks of k/2 threads (--bind-to none, and with mpirun's default binding, one core a rank, which
# rotgen widens: sweep/binding.hpp), and from 8 cores 4 ranks of k/4 threads; one rank of all the
# threads (default binding); then all the cores with --lanes 8 (as threads, as ranks, and from 8
# cores as 4 ranks of threads). ROUNDS (default 5) runs of each, the ways
# interleaved (one of each in turn), the one-thread baseline also at the end of each round; the best
# and the median of each, and the speed-ups of both; every summary.csv is compared with the one-thread run's (with
# lanes, the one-thread lanes run's: DOP853's lanes share steps), byte for byte. A preset
# ROTGEN_CACHE_DIR is kept (a machine that cannot compile the kernels gets them in its cache), and
# mpirun passes it, CXX and LD_LIBRARY_PATH on to the ranks.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/summary_time.sh"
source "$(dirname "${BASH_SOURCE[0]}")/heavy_top_sweep.sh"
rotgen=$(realpath "${1:?usage: sweep_scaling.sh ROTGEN [MEMBERS]}")
members=${2:-16384}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export ROTGEN_CACHE_DIR=${ROTGEN_CACHE_DIR:-$work/cache}
rounds=${ROUNDS:-5}
cores=$(nproc)
run_root=()
[[ $(id -u) == 0 ]] && run_root=(--allow-run-as-root)
heavy_top_sweep "$work/scene.yaml" "$members" "{method: dop853, rtol: 1e-8, atol: 1e-10}"

# The ways, "label|command words" (the scene and -o are added)
ways=("1 thread|sweep -j 1")
for ((k = 2; k <= cores; k *= 2)); do
  ways+=("$k threads (\`-j $k\`)|sweep -j $k")
  ways+=("\`mpirun -n $k\`, 1 thread each|mpirun -n $k sweep -j 1")
  if ((k >= 4)); then
    ways+=("\`mpirun -n 2 --bind-to none -j $((k / 2))\`|mpirun -n 2 --bind-to none sweep -j $((k / 2))")
    ways+=("\`mpirun -n 2 -j $((k / 2))\` (default binding, which rotgen widens)|mpirun -n 2 sweep -j $((k / 2))")
  fi
  ((k >= 8)) && ways+=("\`mpirun -n 4 -j $((k / 4))\`|mpirun -n 4 sweep -j $((k / 4))")
done
# one rank of all the threads: mpirun binds it to one core, and rotgen gives its threads their cores
((cores >= 2)) && ways+=("\`mpirun -n 1 -j $cores\` (default binding, which rotgen widens)|mpirun -n 1 sweep -j $cores")
ways+=("$cores threads, \`--lanes 8\`|sweep -j $cores --lanes 8")
((cores >= 2)) && ways+=("\`mpirun -n $cores --lanes 8\`|mpirun -n $cores sweep -j 1 --lanes 8")
((cores >= 8)) && ways+=("\`mpirun -n 4 -j $((cores / 4)) --lanes 8\`|mpirun -n 4 sweep -j $((cores / 4)) --lanes 8")

# Fresh copies of rotgen and of the kernel cache for a round (new pages: a copy's speed depends on
# where its pages lie in memory on a virtual machine, docs/design-notes.md), which one_run runs
fresh_copies() {
  rm -rf "$work/round" && mkdir -p "$work/round"
  cp "$rotgen" "$work/round/rotgen" && cp -r "$ROTGEN_CACHE_DIR" "$work/round/cache"
}
one_run() { # $1: the way's command words; prints the seconds, leaves $work/out
  local words=($1) cmd=() rotgen=$work/round/rotgen
  rm -rf "$work/out"
  if [[ ${words[0]} == mpirun ]]; then
    local i=1
    cmd=(mpirun --oversubscribe "${run_root[@]}" -x ROTGEN_CACHE_DIR)
    local v
    for v in CXX LD_LIBRARY_PATH; do [[ -n ${!v:-} ]] && cmd+=(-x "$v"); done
    while [[ ${words[i]} != sweep ]]; do cmd+=("${words[i]}"); i=$((i + 1)); done
    cmd+=("$rotgen" "${words[@]:i}")
  else
    cmd=("$rotgen" "${words[@]}")
  fi
  ROTGEN_CACHE_DIR=$work/round/cache "${cmd[@]:0:${#cmd[@]}}" "$work/scene.yaml" -o "$work/out" \
    2>/dev/null | summary_seconds "running the members"
}

"$rotgen" sweep "$work/scene.yaml" -o "$work/reference" -j 1 -q # the kernels into the cache
"$rotgen" sweep "$work/scene.yaml" -o "$work/reference_lanes" -j 1 -q --lanes 8
# times[i]: every run of way i, space-separated. The one-thread way, the baseline, runs at the start
# and at the end of each round: on a virtual machine its time can jump between two levels (2.9 and
# 4.1 s on the 16-core machine), and the speed-ups are only as good as it.
declare -a times
measure() { # $1: the way's index
  local t reference=$work/reference
  t=$(one_run "${ways[$1]#*|}")
  [[ -n $t ]] || { echo "sweep_scaling.sh: no time from ${ways[$1]#*|}" >&2; exit 1; }
  [[ ${ways[$1]} == *--lanes* ]] && reference=$work/reference_lanes
  cmp -s "$work/out/summary.csv" "$reference/summary.csv" ||
    { echo "sweep_scaling.sh: ${ways[$1]%%|*} wrote another summary.csv" >&2; exit 1; }
  times[$1]="${times[$1]:-} $t"
}
for ((round = 1; round <= rounds; round++)); do
  echo "round $round of $rounds" >&2
  fresh_copies
  for i in "${!ways[@]}"; do measure "$i"; done
  measure 0
done
# "best median count" of the times given
stats() { printf '%s\n' $* | sort -g | awk '{ v[NR] = $1 } END {
  printf "%s %s %d", v[1], (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2), NR }'; }

cat <<EOF2
# rotgen sweep: scaling with the cores

\`bash bench/sweep_scaling.sh build/rotgen > bench/results/sweep_scaling.md\`; $cores cores
($(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')), $(mpirun --version | head -1),
load average $(cut -d' ' -f1-3 /proc/loadavg) when it finished.

The heavy top, $members members (initial theta 0.1 .. 1.5), t = 0 .. 10, 101 samples, DOP853
rtol 1e-8; the summary's "running the members" time of $rounds runs of each, interleaved (the one-thread
baseline twice a round), each round from fresh copies of rotgen and its kernels; the speed-ups are over the one-thread run's best and median; every run's
summary.csv is byte-identical to the one-thread run's (with lanes, to the one-thread lanes
run's).

| run | runs | best s | median s | speed-up (best) | speed-up (medians) |
|---|---:|---:|---:|---:|---:|
EOF2
read -r b0 m0 _ <<<"$(stats ${times[0]})"
for i in "${!ways[@]}"; do
  read -r b m n <<<"$(stats ${times[i]})"
  awk -v l="${ways[i]%%|*}" -v b="$b" -v m="$m" -v n="$n" -v b0="$b0" -v m0="$m0" \
    'BEGIN { printf "| %s | %d | %.3g | %.3g | %.2f | %.2f |\n", l, n, b, m, b0 / b, m0 / m }'
done
