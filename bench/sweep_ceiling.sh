#!/usr/bin/env bash
# rotgen sweep — the most any layout (threads, ranks, both) can gain on this machine's cores
# (Markdown on stdout, progress on stderr):
#
#   bash bench/sweep_ceiling.sh build/rotgen [MEMBERS] > bench/results/sweep_ceiling.md
#
# A one-thread sweep (the heavy top of bench/sweep_scaling.sh, MEMBERS members, default 4,096) is run
# alone on the first core, then once on every core at the same time (taskset, one process a core:
# nothing shared but the machine itself), ROUNDS times (default 3), interleaved. If a member costs
# more when every core is busy (shared caches and memory, the clock of a loaded chip, a virtual
# machine's neighbours), the all-at-once runs are slower than the lone one, and no distribution of
# members gains more than cores × (alone / all at once) over one thread. The times are the sweeps'
# own "running the members".
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/summary_time.sh"
source "$(dirname "${BASH_SOURCE[0]}")/heavy_top_sweep.sh"
rotgen=$(realpath "${1:?usage: sweep_ceiling.sh ROTGEN [MEMBERS]}")
members=${2:-4096}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export ROTGEN_CACHE_DIR=${ROTGEN_CACHE_DIR:-$work/cache}
rounds=${ROUNDS:-3}
cores=$(nproc)
heavy_top_sweep "$work/scene.yaml" "$members" "{method: dop853, rtol: 1e-8, atol: 1e-10}"

one() { # $1: the core; prints the seconds
  taskset -c "$1" "$rotgen" sweep "$work/scene.yaml" -o "$work/out$1" -j 1 2>/dev/null |
    summary_seconds "running the members"
}

"$rotgen" sweep "$work/scene.yaml" -o "$work/out0" -j 1 -q # the kernels into the cache
alone=() together=()
for ((round = 1; round <= rounds; round++)); do
  echo "round $round of $rounds" >&2
  alone+=("$(one 0)")
  for ((k = 0; k < cores; k++)); do one "$k" >"$work/t$k" & done
  wait
  for ((k = 0; k < cores; k++)); do together+=("$(cat "$work/t$k")"); done
done

# stats NAME VALUES...: "min median max" of the values
stats() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END {
  printf "%.3g %.3g %.3g", v[1], (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2), v[NR] }'; }
read -r a_min a_med a_max <<<"$(stats "${alone[@]}")"
read -r t_min t_med t_max <<<"$(stats "${together[@]}")"
cat <<EOF
# rotgen sweep: the ceiling of this machine's cores

\`bash bench/sweep_ceiling.sh build/rotgen > bench/results/sweep_ceiling.md\`; $cores cores
($(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')), load average $(cut -d' ' -f1-3 /proc/loadavg)
when it finished.

The heavy top, $members members (initial theta 0.1 .. 1.5), t = 0 .. 10, 101 samples, DOP853 rtol
1e-8, one thread: alone on core 0, and $cores at once (one a core), $rounds rounds; the sweeps' own
"running the members" time in seconds.

| run | runs | min | median | max |
|---|---:|---:|---:|---:|
| alone | ${#alone[@]} | $a_min | $a_med | $a_max |
| $cores at once | ${#together[@]} | $t_min | $t_med | $t_max |

With every core busy a member cost $(awk -v a="$a_med" -v t="$t_med" 'BEGIN { printf "%.2f", t / a }')× its cost alone
(medians), so no layout of threads or ranks gains more than about
$(awk -v a="$a_med" -v t="$t_med" -v c="$cores" 'BEGIN { printf "%.1f", c * a / t }')× over one thread on these $cores cores (against the fastest lone run,
$(awk -v a="$a_min" -v t="$t_med" -v c="$cores" 'BEGIN { printf "%.1f", c * a / t }')×).
EOF
