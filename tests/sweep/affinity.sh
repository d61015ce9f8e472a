#!/usr/bin/env bash
# A sweep warns, in its summary, when its threads outnumber the cores a process may run on (its
# CPU affinity): one process held to one core by taskset, and (given MPIEXEC, on 2 cores or more)
# 2 ranks that mpirun binds to one core each, each running 2 threads; no warning when the threads
# fit (-j 1 on one core; 2 ranks of 2 threads with --bind-to none).
#   affinity.sh ROTGEN SOURCE_DIR [MPIEXEC]
set -euo pipefail
rotgen=${1:?rotgen} src=${2:?source dir} mpiexec=${3:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=$src/models/scenes/heavy_top_nutation.yaml
vary=(--vary initial.theta=0.1:1.5:4)
expect() { # expect yes|no FILE WHAT: whether FILE's summary has the warning
  local found=no
  grep -q '^  warning [0-9]* threads share the [0-9]* core' "$2" && found=yes
  [[ $found == "$1" ]] || { echo "$3: warning $found, expected $1:"; cat "$2"; exit 1; }
}
taskset -c 0 "$rotgen" sweep "$scene" -o "$work/a" "${vary[@]}" -j 2 >"$work/a.txt"
expect yes "$work/a.txt" "taskset -c 0, -j 2"
grep -q "share the 1 core this process may run on" "$work/a.txt" || { cat "$work/a.txt"; exit 1; }
taskset -c 0 "$rotgen" sweep "$scene" -o "$work/b" "${vary[@]}" -j 1 >"$work/b.txt"
expect no "$work/b.txt" "taskset -c 0, -j 1"
if [[ -n $mpiexec ]] && (($(nproc) >= 2)); then
  root=()
  [[ $(id -u) == 0 ]] && root=(--allow-run-as-root)
  "$mpiexec" -n 2 --bind-to core "${root[@]}" "$rotgen" sweep "$scene" -o "$work/c" "${vary[@]}" \
    -j 2 >"$work/c.txt" 2>&1
  expect yes "$work/c.txt" "mpirun -n 2 --bind-to core, -j 2"
  grep -q "an MPI rank may run on (mpirun binds" "$work/c.txt" || { cat "$work/c.txt"; exit 1; }
  "$mpiexec" -n 2 --bind-to none "${root[@]}" "$rotgen" sweep "$scene" -o "$work/d" "${vary[@]}" \
    -j 2 >"$work/d.txt" 2>&1
  expect no "$work/d.txt" "mpirun -n 2 --bind-to none, -j 2"
fi
echo "the oversubscription warning appears exactly when the threads outnumber the cores"
