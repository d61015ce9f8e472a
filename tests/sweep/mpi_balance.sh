#!/usr/bin/env bash
# The dynamic part of the MPI sharing balances members that differ widely in cost: 64 members of
# which 8 cost about 300 times the others (a fast spin), run under `mpirun -n 2 -j 2`. Each rank
# starts on a static block of its own (rank 0 members 0-7, rank 1 members 8-15: a quarter of the
# sweep, shared equally) and the rest comes from the shared counter, so the rank whose block is
# cheap runs more than half of the sweep: once with the expensive members as rank 0's block (rank 1
# must run more than 32), once as rank 1's (rank 0 must). Static shares (32 each) fail this. Every
# summary.csv is one process's byte for byte, with lanes too (when built with them). And with a
# window of 4 members (the tests' hook ROTGEN_TEST_SWEEP_WINDOW), 2 and 3 ranks of 2 threads write
# one process's summary.csv and trajectories.h5: a rank starts only members that fit rank 0's
# window (a member outside it is an internal error that ends the run). The `--timings` lines
# of each rank's share (members, busy time, last member) agree with the ranks line and the run.
#   mpi_balance.sh ROTGEN MPIEXEC SOURCE_DIR LANES(ON|OFF)
set -euo pipefail
rotgen=${1:?rotgen} mpiexec=${2:?mpiexec} src=${3:?source dir} lanes=${4:-OFF}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export ROTGEN_CACHE_DIR=$work/cache
root=()
[[ $(id -u) == 0 ]] && root=(--allow-run-as-root)
# scene NAME FIRST: members FIRST .. FIRST+7 spin at psi_dot 20000+k, the others at 5+k
scene() {
  local values=()
  for ((k = 0; k < 64; k++)); do
    if ((k >= $2 && k < $2 + 8)); then values+=($((20000 + k))); else values+=($((5 + k))); fi
  done
  cat >"$work/$1.yaml" <<YAML
model: $src/models/heavy_top.yaml
initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}
time: {end: 2, samples: 11}
integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}
record: [theta, energy]
sweep:
  vary:
    initial.psi_dot: {values: [$(IFS=,; echo "${values[*]}")]}
YAML
}
# counts FILE: the members each rank ran, from the summary's ranks line
counts() {
  sed -n 's/^  ranks   members run by rank 0, 1, ...: *//p' "$1" | tr -d ,
}
# balance FILE JOBS COUNTS...: FILE's --timings lines, one per rank ("threads" for one process),
# say that each ran COUNTS members, and their times are consistent: a rank's JOBS threads were
# busy for more than 0 s and no longer than JOBS times the span from its first member's start to
# its last member's end, which lies within the members' stage time
balance() {
  local file=$1 jobs=$2
  shift 2
  awk -v jobs="$jobs" -v want="$*" '
    function after(word,   k) { for (k = 1; k < NF; k++) if ($k == word) return $(k + 1) }
    /^rotgen: timing members/ { stage = $4 }
    /^rotgen: (rank [0-9]+|threads) .* members from / {
      for (k = 2; k <= NF; k++) if ($k == "members") n = $(k - 1)
      first = after("from"); last = after("to"); busy = after("busy")
      got = got (got == "" ? "" : " ") n
      if (!(busy > 0 && 0 <= first && first <= last && last <= stage + 0.002 &&
            busy <= jobs * (last - first) + 0.003)) bad = bad "\n" $0
    }
    END {
      if (got != want) { print "balance lines ran " got ", not " want; exit 1 }
      if (bad != "") { print "balance lines with inconsistent times (stage " stage " s):" bad; exit 1 }
    }' "$file" || { cat "$file"; exit 1; }
}
# check NAME WHO EXTRA...: 2 ranks of 2 threads write one process's summary.csv, and rank WHO
# (the one without the expensive members) ran more than half of the 64
check() {
  local name=$1 who=$2 c
  shift 2
  "$rotgen" sweep "$work/$name.yaml" -o "$work/$name.one" -j 1 -q --timings "$@" \
    2>"$work/$name.one.err"
  balance "$work/$name.one.err" 1 64
  "$mpiexec" -n 2 --oversubscribe "${root[@]}" "$rotgen" sweep "$work/$name.yaml" \
    -o "$work/$name.two" -j 2 --timings "$@" >"$work/$name.out" 2>"$work/$name.err"
  cmp "$work/$name.one/summary.csv" "$work/$name.two/summary.csv" ||
    { echo "$name $*: summary.csv differs between 1 process and 2 ranks"; exit 1; }
  read -r -a c <<<"$(counts "$work/$name.out")"
  [[ ${#c[@]} == 2 ]] || { echo "$name: no ranks line: $(cat "$work/$name.out")"; exit 1; }
  ((c[0] > 0 && c[1] > 0 && c[0] + c[1] == 64)) || { echo "$name $*: ranks ran ${c[*]}"; exit 1; }
  ((c[who] > 32)) ||
    { echo "$name $*: rank $who ran ${c[who]} of 64 (${c[*]}): the counter did not balance"; exit 1; }
  balance "$work/$name.err" 2 "${c[@]}"
  echo "$name $*: ranks ran ${c[*]}"
}
# window N: N ranks of 2 threads with a window of 4 members write one process's files
window() {
  local c
  "$mpiexec" -n "$1" --oversubscribe "${root[@]}" -x ROTGEN_TEST_SWEEP_WINDOW=4 "$rotgen" sweep \
    "$work/rank0_heavy.yaml" -o "$work/window$1" -j 2 --trajectories >"$work/window$1.out"
  for f in summary.csv trajectories.h5; do
    cmp "$work/trajectories/$f" "$work/window$1/$f" ||
      { echo "window of 4, $1 ranks: $f differs from 1 process's"; exit 1; }
  done
  read -r -a c <<<"$(counts "$work/window$1.out")"
  [[ ${#c[@]} == "$1" ]] || { echo "window, $1 ranks: no ranks line"; exit 1; }
  echo "window of 4, $1 ranks: ranks ran ${c[*]}"
}
scene rank0_heavy 0
scene rank1_heavy 8
check rank0_heavy 1
check rank1_heavy 0
[[ $lanes == ON ]] && check rank0_heavy 1 --lanes 4
"$rotgen" sweep "$work/rank0_heavy.yaml" -o "$work/trajectories" -j 1 -q --trajectories
window 2
window 3
echo "2 ranks balanced members of unequal cost and wrote one process's summary.csv"
