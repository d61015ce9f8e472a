#!/usr/bin/env bash
# rotgen sweep — two builds of rotgen side by side on MPI ranks (for a change to the distribution:
# sweep/distribute_mpi.cpp), with the newer one's threads on the same cores as the yardstick
# (Markdown on stdout, progress on stderr):
#
#   [RANKS=2] [ROUNDS=5] bash bench/sweep_ranks_ab.sh OLD_ROTGEN NEW_ROTGEN [MEMBERS] \
#     > bench/results/sweep_naps.md
#
# The heavy top (bench/heavy_top_sweep.sh), MEMBERS (default 16,384) members, DOP853 rtol 1e-8;
# `mpirun -n RANKS` (default 2) ranks of one thread each as they are, with --lanes 8 and with
# --trajectories (large messages), for both builds, and `-j RANKS` threads of the new one; ROUNDS (default 5) rounds, every
# way once a round in turn, each round from fresh copies of both builds; the summary's "running
# the members" time, best and median. Every run's summary.csv is compared with the first round's
# of the same options, byte for byte.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/summary_time.sh"
source "$(dirname "${BASH_SOURCE[0]}")/heavy_top_sweep.sh"
old=$(realpath "${1:?usage: sweep_ranks_ab.sh OLD_ROTGEN NEW_ROTGEN [MEMBERS]}")
new=$(realpath "${2:?usage: sweep_ranks_ab.sh OLD_ROTGEN NEW_ROTGEN [MEMBERS]}")
members=${3:-16384}
rounds=${ROUNDS:-5}
ranks=${RANKS:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export ROTGEN_CACHE_DIR=$work/cache
root=() pass=() # mpirun passes CXX and LD_LIBRARY_PATH on to the ranks where they are set
[[ $(id -u) == 0 ]] && root=(--allow-run-as-root)
for v in CXX LD_LIBRARY_PATH; do [[ -n ${!v:-} ]] && pass+=(-x "$v"); done
heavy_top_sweep "$work/scene.yaml" "$members" "{method: dop853, rtol: 1e-8, atol: 1e-10}"
options=("" "--lanes 8" "--trajectories")
"$new" sweep "$work/scene.yaml" -o "$work/warm" -j 1 -q --lanes 8 # the kernels into the cache

declare -A times
one_run() { # $1: old|new|threads, $2: the options' index; adds the seconds to times
  local opts=(${options[$2]}) cmd=()
  case $1 in
    old | new) cmd=(mpirun "${root[@]}" --oversubscribe -x ROTGEN_CACHE_DIR "${pass[@]}" -n "$ranks"
      "$work/$1" sweep -j 1) ;;
    threads) cmd=("$work/new" sweep -j "$ranks") ;;
  esac
  rm -rf "$work/out"
  local t
  t=$("${cmd[@]}" "$work/scene.yaml" -o "$work/out" "${opts[@]}" | summary_seconds "running the members")
  [[ -n $t ]] || { echo "sweep_ranks_ab.sh: no time from $1 ${options[$2]}" >&2; exit 1; }
  if [[ -e $work/reference$2 ]]; then
    cmp -s "$work/out/summary.csv" "$work/reference$2" ||
      { echo "sweep_ranks_ab.sh: $1 ${options[$2]} wrote another summary.csv" >&2; exit 1; }
  else
    cp "$work/out/summary.csv" "$work/reference$2"
  fi
  times[$1,$2]="${times[$1,$2]:-} $t"
}
for ((round = 1; round <= rounds; round++)); do
  echo "round $round of $rounds" >&2
  cp "$old" "$work/old" && cp "$new" "$work/new"
  for i in "${!options[@]}"; do
    for way in old new threads; do one_run "$way" "$i"; done
  done
done
stats() { printf '%s\n' $* | sort -g | awk '{ v[NR] = $1 } END {
  printf "%.3g %.3g", v[1], (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }

cat <<EOF2
# rotgen sweep: two builds on MPI ranks

\`bash bench/sweep_ranks_ab.sh OLD NEW > bench/results/sweep_naps.md\`; $(nproc) cores
($(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')), $(mpirun --version | head -1).
OLD: $(cd "$(dirname "$old")" && git log -1 --format=%h 2>/dev/null || echo "?"), NEW: $(cd "$(dirname "$new")" && git log -1 --format=%h 2>/dev/null || echo "?") (the commits of the trees the builds are in; a build may hold uncommitted changes).

The heavy top, $members members, DOP853 rtol 1e-8, t = 0 .. 10, 101 samples; the summary's "running
the members" time in seconds, best and median of $rounds interleaved runs; \`mpirun -n $ranks\` is one
thread a rank; every summary.csv of an option is byte-identical.

| options | OLD, \`mpirun -n $ranks\` best | median | NEW, \`mpirun -n $ranks\` best | median | NEW, \`-j $ranks\` best | median |
|---|---:|---:|---:|---:|---:|---:|
EOF2
for i in "${!options[@]}"; do
  row="| ${options[$i]:-(none)} "
  for way in old new threads; do
    read -r b m <<<"$(stats ${times[$way,$i]})"
    row+="| $b | $m "
  done
  echo "$row|"
done
