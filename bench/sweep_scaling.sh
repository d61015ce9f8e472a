#!/usr/bin/env bash
# rotgen sweep — how the members' time scales with the cores this machine has, as threads, as MPI
# ranks and as both (Markdown on stdout, progress on stderr):
#
#   bash bench/sweep_scaling.sh build/rotgen [MEMBERS] > bench/results/sweep_scaling.md
#
# The heavy top (models/heavy_top.yaml), MEMBERS (default 16,384) members over initial theta
# 0.1 .. 1.5, t = 0 .. 10, DOP853 rtol 1e-8, the summary's "running the members" time. For each
# power of two k up to the cores (nproc): k threads, k ranks of one thread, and above 2 cores 2
# ranks of k/2 threads (--bind-to none, and with mpirun's default binding, which the summary warns
# about), and from 8 cores 4 ranks of k/4 threads; then all the cores with --lanes 8 (as threads, as
# ranks, and from 8 cores as 4 ranks of threads). Best of ROUNDS (default 5) runs of each, the ways
# interleaved (one of each in turn); every summary.csv is compared with the one-thread run's (with
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
    ways+=("\`mpirun -n 2 -j $((k / 2))\` (default binding)|mpirun -n 2 sweep -j $((k / 2))")
  fi
  ((k >= 8)) && ways+=("\`mpirun -n 4 -j $((k / 4))\`|mpirun -n 4 sweep -j $((k / 4))")
done
ways+=("$cores threads, \`--lanes 8\`|sweep -j $cores --lanes 8")
((cores >= 2)) && ways+=("\`mpirun -n $cores --lanes 8\`|mpirun -n $cores sweep -j 1 --lanes 8")
((cores >= 8)) && ways+=("\`mpirun -n 4 -j $((cores / 4)) --lanes 8\`|mpirun -n 4 sweep -j $((cores / 4)) --lanes 8")

one_run() { # $1: the way's command words; prints the seconds, leaves $work/out
  local words=($1) cmd=()
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
  "${cmd[@]:0:${#cmd[@]}}" "$work/scene.yaml" -o "$work/out" 2>/dev/null |
    summary_seconds "running the members"
}

"$rotgen" sweep "$work/scene.yaml" -o "$work/reference" -j 1 -q # the kernels into the cache
"$rotgen" sweep "$work/scene.yaml" -o "$work/reference_lanes" -j 1 -q --lanes 8
declare -a best
for ((round = 1; round <= rounds; round++)); do
  echo "round $round of $rounds" >&2
  for i in "${!ways[@]}"; do
    t=$(one_run "${ways[i]#*|}")
    [[ -n $t ]] || { echo "sweep_scaling.sh: no time from ${ways[i]#*|}" >&2; exit 1; }
    reference=$work/reference
    [[ ${ways[i]} == *--lanes* ]] && reference=$work/reference_lanes
    cmp -s "$work/out/summary.csv" "$reference/summary.csv" ||
      { echo "sweep_scaling.sh: ${ways[i]%%|*} wrote another summary.csv" >&2; exit 1; }
    if [[ -z ${best[i]:-} ]] || awk -v a="$t" -v b="${best[i]}" 'BEGIN { exit !(a < b) }'; then
      best[i]=$t
    fi
  done
done

cat <<EOF2
# rotgen sweep: scaling with the cores

\`bash bench/sweep_scaling.sh build/rotgen > bench/results/sweep_scaling.md\`; $cores cores
($(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')), $(mpirun --version | head -1),
load average $(cut -d' ' -f1-3 /proc/loadavg) when it finished.

The heavy top, $members members (initial theta 0.1 .. 1.5), t = 0 .. 10, 101 samples, DOP853
rtol 1e-8; the summary's "running the members" time, best of $rounds runs of each, interleaved; every
run's summary.csv is byte-identical to the one-thread run's (with lanes, to the one-thread lanes
run's).

| run | seconds | speed-up over 1 thread |
|---|---:|---:|
EOF2
for i in "${!ways[@]}"; do
  awk -v l="${ways[i]%%|*}" -v t="${best[i]}" -v b="${best[0]}" \
    'BEGIN { printf "| %s | %.3g | %.2f |\n", l, t, b / t }'
done
