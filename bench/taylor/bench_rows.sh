#!/usr/bin/env bash
# The `taylor` rows of `rotgen bench` on the two scenes of the Taylor comparison (the free top in
# the body form, t = 0..100; the heavy top, t = 0..10), for one rotgen or two side by side:
#   bash bench/taylor/bench_rows.sh NEW_ROTGEN [OLD_ROTGEN] > bench/results/taylor_bench_rows.md
# Each rotgen runs `rotgen bench` once per scene (into its own kernel cache): the errors and
# expansions of the rows, and the scene's compiled driver and plan. The times are then the
# driver's own (the median of its 7 timed loops of one whole integration) on the plan's taylor
# rows alone, ROUNDS times (default 9), each round from fresh copies of the drivers, old and new
# in turn: a copy's speed depends on where its pages lie in memory (on this virtual machine, 20
# copies of one kernel took 361-453 ns an expansion and one 808 ns), so a round's copy is a draw
# and the table gives medians over rounds (after / before: the median of the ratios within a
# round).
set -euo pipefail
cd "$(dirname "$0")/../.."
new=$1
old=${2:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tols="1e-08 1e-10 1e-12 1e-14 1e-15"
scenes="free_top_workprecision heavy_top_nutation"

rounds=${ROUNDS:-9}
for which in old new; do
  bin=${!which}
  [ -n "$bin" ] || continue
  for scene in $scenes; do
    ROTGEN_CACHE_DIR=$work/cache-$which "$bin" bench "models/scenes/$scene.yaml" -o "$work/$which-$scene" >/dev/null
    # the plan without its long runs, and of its runs the taylor ones
    awk '$1 != "drift" && ($1 != "run" || ($3 == "rotgen" && $4 == "taylor"))' \
        "$work/$which-$scene/plan.txt" >"$work/$which-$scene.plan"
    drivers=("$work/cache-$which/bench/$scene"-*/driver)
    [ ${#drivers[@]} -eq 1 ] || { echo "bench_rows.sh: no single driver for $scene" >&2; exit 1; }
    cp "${drivers[0]}" "$work/$which-$scene.driver"
  done
done
# "round tol time_us" of a driver's raw output $1 (its taylor rows)
raw_rows() {
  awk -v r="$2" '$1 == "row" && $3 == "rotgen" && $4 == "taylor" { printf "%d %.0e %.2f\n", r, $7, $15 * 1e6 }' "$1"
}
for ((r = 1; r <= rounds; r++)); do
  echo "round $r of $rounds" >&2
  for scene in $scenes; do
    for which in old new; do
      [ -n "${!which}" ] || continue
      cp "$work/$which-$scene.driver" "$work/copy" # fresh pages
      "$work/copy" "$work/$which-$scene.plan" "$work/raw" >/dev/null
      raw_rows "$work/raw" "$r" >>"$work/$which-$scene.times"
      rm "$work/copy"
    done
  done
done
# "tol error expansions" of the taylor rows of results.csv $1
rows() {
  awk -F, 'NR > 1 && $1 == "taylor" { printf "%.0e %s %s\n", $5, $7, $9 }' "$1"
}

# The median of the numbers on standard input
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
# The times of tolerance $2 in $1 ("round tol time_us"), one per round, in round order
times_of() { awk -v t="$2" '$2 + 0 == t + 0 { print $3 }' "$1"; }
# Field $3 of the row of tolerance $2 in results.csv $1 (2 error, 3 expansions)
field() { rows "$1" | awk -v f="$3" -v t="$2" '$1 + 0 == t + 0 { print $f }'; }

echo "# The \`taylor\` rows of \`rotgen bench\`"
echo
echo "\`bash bench/taylor/bench_rows.sh $new${old:+ $old}\`; $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')),"
echo "load average $(cut -d' ' -f1-3 /proc/loadavg) when it finished. Time: the bench driver's median of 7 timed"
echo "loops of one whole integration, the median of $rounds rounds, each from fresh copies of the drivers"
if [ -n "$old" ]; then
  echo "(after / before: the median of the ratios within each round); error and expansions: the bench's,"
else
  echo "; error and expansions: the bench's,"
fi
echo "the bench's error column (since 8f3dce0 the largest over the samples; before it, the final state's error)."
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
    n=$(field "$work/new-$scene/results.csv" "$tol" 2)
    [ -n "$n" ] || continue
    steps=$(field "$work/new-$scene/results.csv" "$tol" 3)
    t_new=$(times_of "$work/new-$scene.times" "$tol" | median)
    if [ -n "$old" ]; then
      e_old=$(field "$work/old-$scene/results.csv" "$tol" 2)
      t_old=$(times_of "$work/old-$scene.times" "$tol" | median)
      ratio=$(paste <(times_of "$work/new-$scene.times" "$tol") <(times_of "$work/old-$scene.times" "$tol") |
              awk '{ print $1 / $2 }' | median)
      echo "| $tol | $e_old | $n | $steps | $t_old | $t_new | $(awk -v r="$ratio" 'BEGIN { printf "%.2f", r }') |"
    else
      echo "| $tol | $n | $steps | $t_new |"
    fi
  done
done
