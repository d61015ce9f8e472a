#!/usr/bin/env bash
# The `taylor` rows of `rotgen bench` on the two scenes of the Taylor comparison (the free top in
# the body form, t = 0..100; the heavy top, t = 0..10), for one rotgen or two side by side:
#   bash bench/taylor/bench_rows.sh NEW_ROTGEN [OLD_ROTGEN] > bench/results/taylor_bench_rows.md
# With two, the benches alternate (old, new per scene), ROUNDS times (default 3), and the table gives
# per tolerance the median over the rounds of each time and of new/old within a round (a pair run
# a minute apart: the shared machine's speed drifts more than that between rounds).
# Each time is the bench's own: the median of its 7 timed loops (`time_median_s`).
set -euo pipefail
cd "$(dirname "$0")/../.."
new=$1
old=${2:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tols="1e-08 1e-10 1e-12 1e-14 1e-15"
scenes="free_top_workprecision heavy_top_nutation"

# "tol error steps_or_evals time_us" of the taylor rows of results.csv $1
rows() {
  awk -F, 'NR > 1 && $1 == "taylor" { printf "%s %s %s %.1f\n", $5, $7, $9, $11 * 1e6 }' "$1"
}

rounds=${ROUNDS:-3}
[ -n "$old" ] || rounds=1
for ((r = 1; r <= rounds; r++)); do
  for scene in $scenes; do
    for which in old new; do
      bin=${!which}
      [ -n "$bin" ] || continue
      "$bin" bench "models/scenes/$scene.yaml" -o "$work/$which-$scene" >/dev/null
      rows "$work/$which-$scene/results.csv" | sed "s/^/$r /" >> "$work/$which-$scene.rows"
    done
  done
done

# The median of the numbers on standard input
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
# Field $2 of the rows of tolerance $3 in $1 ("round tol error steps time_us"), one per round
field() { awk -v f="$2" -v t="$3" '$2 + 0 == t + 0 { print $f }' "$1"; }

echo "# The \`taylor\` rows of \`rotgen bench\`"
echo
echo "\`bash bench/taylor/bench_rows.sh $new${old:+ $old}\`; $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')),"
echo "load average $(cut -d' ' -f1-3 /proc/loadavg) when it finished. Time: the bench's median of 7 timed"
if [ -n "$old" ]; then
  echo "loops of one whole integration, the median of $rounds rounds (after / before: the median of the"
  echo "ratios within each round); error: the bench's, the final state's max-norm error against the"
else
  echo "loops of one whole integration; error: the bench's, the final state's max-norm error against the"
fi
echo "scene's reference."
for scene in $scenes; do
  echo
  echo "### $scene"
  echo
  if [ -n "$old" ]; then
    echo "| tol | error before | error after | expansions | µs before | µs after | after / before |"
    echo "|---|---:|---:|---:|---:|---:|---:|"
  else
    echo "| tol | error | expansions | µs |"
    echo "|---|---:|---:|---:|"
  fi
  for tol in $tols; do
    n=$(field "$work/new-$scene.rows" 3 "$tol" | head -1)
    [ -n "$n" ] || continue
    steps=$(field "$work/new-$scene.rows" 4 "$tol" | head -1)
    t_new=$(field "$work/new-$scene.rows" 5 "$tol" | median)
    if [ -n "$old" ]; then
      e_old=$(field "$work/old-$scene.rows" 3 "$tol" | head -1)
      t_old=$(field "$work/old-$scene.rows" 5 "$tol" | median)
      ratio=$(paste <(field "$work/new-$scene.rows" 5 "$tol") <(field "$work/old-$scene.rows" 5 "$tol") |
              awk '{ print $1 / $2 }' | median)
      echo "| $tol | $e_old | $n | $steps | $t_old | $t_new | $(awk -v r="$ratio" 'BEGIN { printf "%.2f", r }') |"
    else
      echo "| $tol | $n | $steps | $t_new |"
    fi
  done
done
