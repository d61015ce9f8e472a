#!/usr/bin/env bash
# A sweep under `mpirun -n 2` and `-n 3` writes the same files, byte for byte, as one process with
# one thread: summary.csv (with a failed member and an event column) and trajectories.h5; every
# rank runs members and the counts the summary reports add up; a 2-rank sweep interrupted after 5
# journal chunks (the test hook ROTGEN_TEST_SWEEP_INTERRUPT: rank 0 raises SIGTERM; one line says
# so, rank 1 stays quiet) and finished
# by `--resume` under 2 ranks writes the same files too.
#   mpi_sweep.sh ROTGEN MPIEXEC SOURCE_DIR
set -euo pipefail
rotgen=${1:?rotgen} mpiexec=${2:?mpiexec} src=${3:?source dir}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat >"$work/scene.yaml" <<YAML
model: $src/models/heavy_top.yaml
initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}
time: {end: 2, samples: 101}
integrator: {method: dop853, rtol: 1e-10, atol: 1e-12, max_steps: 300}
record: [theta, energy, body_z]
events:
  - {name: turn, when: theta_dot, direction: falling}
sweep:
  vary:
    initial.theta: {from: 0.2, to: 1.4, count: 7}
    initial.psi_dot: {values: [5, 30, 2000]}
YAML
status=0
"$rotgen" sweep "$work/scene.yaml" -o "$work/one" -j 1 --trajectories -q || status=$?
[[ $status == 3 ]] || { echo "one process: exit $status, expected 3 (the psi_dot 2000 members)"; exit 1; }
root=()
[[ $(id -u) == 0 ]] && root=(--allow-run-as-root)
same() { # same DIR WHAT: DIR's files are one process's
  for f in summary.csv trajectories.h5; do
    cmp "$work/one/$f" "$1/$f" || { echo "$f differs between 1 process and $2"; exit 1; }
  done
  [[ $(ls "$1") == $'summary.csv\ntrajectories.h5' ]] || { echo "$2 left: $(ls "$1")"; exit 1; }
}
# ranks N DIR: the members each rank ran (the summary's ranks line) all > 0, adding up to 21
ranks() {
  local line counts sum=0
  line=$(grep '^  ranks   members run by rank 0, 1, ...:' "$2") || { echo "no ranks line: $(cat "$2")"; exit 1; }
  read -r -a counts <<<"$(sed 's/.*://; s/,//g' <<<"$line")"
  [[ ${#counts[@]} == "$1" ]] || { echo "$1 ranks, but the line says: $line"; exit 1; }
  for c in "${counts[@]}"; do
    ((c > 0)) || { echo "a rank ran no member: $line"; exit 1; }
    sum=$((sum + c))
  done
  [[ $sum == 21 ]] || { echo "the ranks ran $sum members, not 21: $line"; exit 1; }
}
for n in 2 3; do
  status=0
  "$mpiexec" -n $n --oversubscribe "${root[@]}" "$rotgen" sweep "$work/scene.yaml" \
    -o "$work/ranks$n" --trajectories >"$work/err$n" 2>&1 || status=$?
  [[ $status == 3 ]] || { echo "mpirun -n $n: exit $status, expected 3"; cat "$work/err$n"; exit 1; }
  same "$work/ranks$n" "$n ranks"
  ranks $n "$work/err$n"
done
head -1 "$work/one/summary.csv" | grep -q ',event.turn,drift.energy,' ||
  { echo "summary.csv has no event.turn column"; exit 1; }
rows=$(($(wc -l <"$work/one/summary.csv") - 1))
[[ $rows == 21 ]] || { echo "summary.csv has $rows members, expected 21"; exit 1; }
# interrupted after 5 chunks (one member each), then resumed, both under 2 ranks
status=0
"$mpiexec" -n 2 --oversubscribe "${root[@]}" -x ROTGEN_TEST_SWEEP_INTERRUPT=5 "$rotgen" sweep \
  "$work/scene.yaml" -o "$work/resumed" --trajectories -q 2>"$work/err" || status=$?
[[ $status != 0 && $status != 3 ]] || { echo "interrupted: exit $status"; exit 1; }
grep -q "^rotgen: interrupted; kept the journal $work/resumed/summary.partial.csv (5 members)" \
  "$work/err" || { echo "no journal line: $(cat "$work/err")"; exit 1; }
# ... said once: rank 1, ended by mpirun's SIGTERM, says nothing
[[ $(grep -c '^rotgen: ' "$work/err") == 1 ]] || { echo "not one line: $(cat "$work/err")"; exit 1; }
[[ $(($(wc -l <"$work/resumed/summary.partial.csv") - 1)) == 5 ]] ||
  { echo "the journal does not hold 5 members"; exit 1; }
status=0
"$mpiexec" -n 2 --oversubscribe "${root[@]}" "$rotgen" sweep "$work/scene.yaml" \
  -o "$work/resumed" --trajectories -q --resume || status=$?
[[ $status == 3 ]] || { echo "resumed: exit $status, expected 3"; exit 1; }
same "$work/resumed" "2 ranks, interrupted and resumed"
echo "2 and 3 ranks, and 2 ranks interrupted and resumed, wrote the same summary.csv and" \
  "trajectories.h5 as 1 process ($rows members); every rank ran members"
