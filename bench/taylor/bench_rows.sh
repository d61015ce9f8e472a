#!/usr/bin/env bash
# The `taylor` rows of `rotgen bench` on the two scenes of the Taylor comparison (the free top in
# the body form, t = 0..100; the heavy top, t = 0..10), for one rotgen or two side by side:
#   bash bench/taylor/bench_rows.sh NEW_ROTGEN [OLD_ROTGEN] > bench/results/taylor_bench_rows.md
# With two, the benches alternate (old, new per scene) and the table gives new/old per tolerance.
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

for scene in $scenes; do
  for which in old new; do
    bin=${!which}
    [ -n "$bin" ] || continue
    "$bin" bench "models/scenes/$scene.yaml" -o "$work/$which-$scene" >/dev/null
    rows "$work/$which-$scene/results.csv" > "$work/$which-$scene.rows"
  done
done

echo "# The \`taylor\` rows of \`rotgen bench\`"
echo
echo "\`bash bench/taylor/bench_rows.sh $new${old:+ $old}\`; $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')),"
echo "load average $(cut -d' ' -f1-3 /proc/loadavg) when it finished. Time: the bench's median of 7 timed"
echo "loops of one whole integration; error: the bench's, the final state's max-norm error against"
echo "the scene's reference."
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
    n=$(awk -v t="$tol" '$1 + 0 == t + 0' "$work/new-$scene.rows")
    [ -n "$n" ] || continue
    set -- $n
    if [ -n "$old" ]; then
      o=$(awk -v t="$tol" '$1 + 0 == t + 0' "$work/old-$scene.rows")
      set -- $n $o
      echo "| $tol | $6 | $2 | $3 | $8 | $4 | $(awk -v a="$4" -v b="$8" 'BEGIN { printf "%.2f", a / b }') |"
    else
      echo "| $tol | $2 | $3 | $4 |"
    fi
  done
done
