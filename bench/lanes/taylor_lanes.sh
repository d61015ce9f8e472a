#!/usr/bin/env bash
# rotgen sweep --lanes with the Taylor method (Markdown on stdout, progress on stderr):
#
#   bash bench/lanes/taylor_lanes.sh build/rotgen > bench/results/taylor_lanes.md
#
# The heavy top of bench/sweep.sh (models/heavy_top.yaml, 1024 members over initial theta
# 0.1 .. 1.5, t = 0 .. 10, 101 samples), integrated by `taylor` at rtol = atol = 1e-12: on one
# thread, one member at a time, with `--lanes 4`, `--lanes 8` (8-wide on AVX-512) and `--lanes 8`
# in AVX2 batches (ROTGEN_LANES_TARGET=avx2); the same to t = 0.01 (a
# member's cost outside its integration). Each figure is the median of 21 rounds of the sweep's own
# "running the members" time (kernels compiled once, before; each round from fresh copies of the
# binary and the kernels, below), the ways interleaved in each round so that all see the same load.
# Timing claims live here, never in ctest.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../summary_time.sh"
source "$(dirname "${BASH_SOURCE[0]}")/../heavy_top_sweep.sh"
rotgen=$(realpath "${1:?usage: taylor_lanes.sh ROTGEN}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export ROTGEN_CACHE_DIR=${ROTGEN_CACHE_DIR:-$work/cache} # the libraries timed below are these
members=1024 runs=${RUNS:-21}

heavy_top_sweep "$work/taylor.yaml" "$members" "{method: taylor, rtol: 1e-12, atol: 1e-12}"
sed 's/end: 10,/end: 0.01,/' "$work/taylor.yaml" >"$work/short.yaml"

# Each round runs from fresh copies of the rotgen binary and of the kernel cache: on this machine
# (a virtual one) the same bytes of a compiled kernel run at speeds that depend on where their
# file's pages happen to lie in memory: 20 copies of one heavy-top Taylor kernel took 361-453 ns
# per expansion, and one 808 ns, and a copy keeps its speed as long as its pages stay cached. A
# best of runs of one copy measures that copy; the median over copies measures the code.
round_dir=$work/round
fresh_copies() {
  rm -rf "$round_dir" && mkdir -p "$round_dir"
  cp "$rotgen" "$round_dir/rotgen" && cp -r "$ROTGEN_CACHE_DIR" "$round_dir/cache"
}
# "WALL CPU" of one sweep of $1 with the options $2... from this round's copies: WALL the sweep's
# own "running the members" seconds, CPU the command's user + system seconds (preparation
# included) from /usr/bin/time
one_run() {
  local scene=$1 t
  shift
  rm -rf "$work/out"
  t=$(ROTGEN_CACHE_DIR=$round_dir/cache /usr/bin/time -f "cpu %U %S" -o "$work/cpu" \
      env $lane_env "$round_dir/rotgen" sweep "$scene" -o "$work/out" -j 1 "$@" 2>&1 |
      summary_seconds "running the members")
  [[ -n $t ]] || { echo "taylor_lanes.sh: no time from: $scene $*" >&2; exit 1; }
  echo "$t $(awk '/^cpu/ { print $2 + $3 }' "$work/cpu")"
}
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
# the ways: alone, --lanes 4, --lanes 8 (8-wide batches where the CPU has AVX-512), and --lanes 8
# in 4-wide AVX2 batches (ROTGEN_LANES_TARGET=avx2: issue 29's measure)
ways=("" "--lanes 4" "--lanes 8" "--lanes 8")
envs=("" "" "" "ROTGEN_LANES_TARGET=avx2")
for k in 0 1 2 3; do # compile the kernels into the cache
  # shellcheck disable=SC2086
  env ${envs[k]} "$rotgen" sweep "$work/taylor.yaml" -o "$work/warm" -q -j 1 ${ways[k]}
done
summary=$("$rotgen" sweep "$work/taylor.yaml" -o "$work/out" -j 1 --lanes 8 2>&1)
lanes_line=$(sed -n 's/^  lanes   //p' <<<"$summary")
lanes_arch=$(sed -n 's/.*(\(.*\))$/\1/p' <<<"$lanes_line")
steps_lanes=$(sed -n 's/^  steps   //p' <<<"$summary")
steps_alone=$("$rotgen" sweep "$work/taylor.yaml" -o "$work/out" -j 1 2>&1 | sed -n 's/^  steps   //p')
# Every round: fresh copies, then the ways on both scenes (interleaved, so that all see the same
# load). Leaves "WALL CPU" per run in $work/times/SCENE-WAY.
mkdir -p "$work/times"
for ((r = 0; r < runs; r++)); do
  echo "round $((r + 1)) of $runs" >&2
  fresh_copies
  for scene in taylor short; do
    for k in 0 1 2 3; do
      # shellcheck disable=SC2086
      lane_env=${envs[k]} one_run "$work/$scene.yaml" ${ways[k]} >>"$work/times/$scene-$k"
    done
  done
done
# the median of column $2 (1 wall, 2 CPU) over the rounds of $1 (SCENE-WAY)
med() { awk -v c="$2" '{ print $c }' "$work/times/$1" | median; }
best() { awk '{ print $1 }' "$work/times/$1" | sort -g | head -1; }
read -r one one_c l4 l4_c l8 l8_c <<<"$(med taylor-0 1) $(med taylor-0 2) $(med taylor-1 1) $(med taylor-1 2) $(med taylor-2 1) $(med taylor-2 2)"
read -r s_one s_one_c s_l4 s_l4_c s_l8 s_l8_c <<<"$(med short-0 1) $(med short-0 2) $(med short-1 1) $(med short-1 2) $(med short-2 1) $(med short-2 2)"
read -r b_one b_l4 b_l8 <<<"$(best taylor-0) $(best taylor-1) $(best taylor-2)"
read -r a8 a8_c s_a8 s_a8_c b_a8 <<<"$(med taylor-3 1) $(med taylor-3 2) $(med short-3 1) $(med short-3 2) $(best taylor-3)"

ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
us() { awk -v t="$1" -v n=$members 'BEGIN { printf "%.0f", t / n * 1e6 }'; }
sub_us() { awk -v a="$1" -v b="$2" -v n=$members 'BEGIN { printf "%.0f", (a - b) / n * 1e6 }'; }
cat <<EOF
# rotgen sweep --lanes with the Taylor method

\`bash bench/lanes/taylor_lanes.sh build/rotgen > bench/results/taylor_lanes.md\`; $(nproc) cores
($(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')), load average $(cut -d' ' -f1-3 /proc/loadavg)
when it finished. Each figure is the median of $runs rounds, each round from fresh copies of the
rotgen binary and of the compiled kernels (a copy's speed depends on where its pages lie in memory
on this virtual machine: 20 copies of one Taylor kernel took 361-453 ns an expansion, one of them
808), the ways interleaved in each round; the best round's wall time is in the second column.

The heavy top of \`bench/sweep.sh\`: $members members (initial theta 0.1 .. 1.5), t = 0 .. 10, 101
samples, \`taylor\` at rtol = atol = 1e-12, one thread; the time is the sweep's own "running the
members" (the kernels compiled once, before).

| run | wall s, median | best s | wall µs per member | speed-up | integration alone, wall µs per member | its speed-up | CPU µs per member | integration alone, CPU µs per member | its speed-up |
|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|
| one member at a time | $one | $b_one | $(us "$one") | 1 | $(sub_us "$one" "$s_one") | 1 | $(us "$one_c") | $(sub_us "$one_c" "$s_one_c") | 1 |
| \`--lanes 4\` | $l4 | $b_l4 | $(us "$l4") | $(ratio "$one" "$l4") | $(sub_us "$l4" "$s_l4") | $(ratio "$(sub_us "$one" "$s_one")" "$(sub_us "$l4" "$s_l4")") | $(us "$l4_c") | $(sub_us "$l4_c" "$s_l4_c") | $(ratio "$(sub_us "$one_c" "$s_one_c")" "$(sub_us "$l4_c" "$s_l4_c")") |
| \`--lanes 8\`, 4-wide AVX2 batches (\`ROTGEN_LANES_TARGET=avx2\`) | $a8 | $b_a8 | $(us "$a8") | $(ratio "$one" "$a8") (goal 2.5) | $(sub_us "$a8" "$s_a8") | $(ratio "$(sub_us "$one" "$s_one")" "$(sub_us "$a8" "$s_a8")") | $(us "$a8_c") | $(sub_us "$a8_c" "$s_a8_c") | $(ratio "$(sub_us "$one_c" "$s_one_c")" "$(sub_us "$a8_c" "$s_a8_c")") |
| \`--lanes 8\` ($lanes_arch) | $l8 | $b_l8 | $(us "$l8") | $(ratio "$one" "$l8") | $(sub_us "$l8" "$s_l8") | $(ratio "$(sub_us "$one" "$s_one")" "$(sub_us "$l8" "$s_l8")") | $(us "$l8_c") | $(sub_us "$l8_c" "$s_l8_c") | $(ratio "$(sub_us "$one_c" "$s_one_c")" "$(sub_us "$l8_c" "$s_l8_c")") |
| to t = 0.01 (a member's cost outside its integration) | $s_one | | $(us "$s_one") | | | | $(us "$s_one_c") | | |
| the same, \`--lanes 4\` | $s_l4 | | $(us "$s_l4") | | | | $(us "$s_l4_c") | | |
| the same, \`--lanes 8\`, AVX2 | $s_a8 | | $(us "$s_a8") | | | | $(us "$s_a8_c") | | |
| the same, \`--lanes 8\` ($lanes_arch) | $s_l8 | | $(us "$s_l8") | | | | $(us "$s_l8_c") | | |

"Integration alone" is the run to t = 10 minus the run to t = 0.01. CPU: the whole command's user +
system time (its preparation, the same in every row, cancels in "integration alone"); on a loaded
machine it moves less than the wall time, which counts the time the process waits for a core. The summary of the \`--lanes 8\`
sweep: lanes $lanes_line; steps $steps_lanes (one member at a time: $steps_alone; a batch takes
the smallest of its lanes' steps).
EOF
