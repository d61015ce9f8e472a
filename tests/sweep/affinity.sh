#!/usr/bin/env bash
# A sweep warns, in its summary, when its threads outnumber the cores a process may run on (its
# CPU affinity): one process held to one core by taskset; no warning when the threads fit (-j 1
# on one core). Given MPIEXEC, on 2 cores or more: a rank that mpirun binds to one core gets cores
# for its threads (sweep/binding.hpp), with the same summary.csv, unless ROTGEN_BINDING=keep or
# mpirun itself is held to that core (taskset), and then it warns; 2 ranks of 2 threads on 2 cores
# share them, bound or not, with a warning; an unknown ROTGEN_BINDING is bad input.
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
  mpi() { # mpi OUT MPIRUN_ARGS... -- SWEEP_ARGS...: one sweep under mpirun, its summary in OUT.txt
    local out=$1 launch=()
    shift
    while [[ $1 != -- ]]; do launch+=("$1") && shift; done
    shift
    "$mpiexec" "${root[@]}" "${launch[@]}" "$rotgen" sweep "$scene" -o "$work/$out" "${vary[@]}" \
      "$@" >"$work/$out.txt" 2>&1
  }
  # mpirun binds one rank to one core: rotgen gives its 2 threads 2 cores (same summary.csv)
  mpi e -n 1 --bind-to core -x ROTGEN_BINDING= -- -j 2
  expect no "$work/e.txt" "mpirun -n 1 --bind-to core, -j 2"
  grep -q "^  cores   the launcher bound each rank to 1 core, too few for its threads: rotgen gave it 2 cores of its own" \
    "$work/e.txt" || { cat "$work/e.txt"; exit 1; }
  cmp "$work/a/summary.csv" "$work/e/summary.csv"
  # ... unless ROTGEN_BINDING=keep, and then it warns
  ROTGEN_BINDING=keep mpi f -n 1 --bind-to core -x ROTGEN_BINDING -- -j 2
  expect yes "$work/f.txt" "mpirun -n 1 --bind-to core, ROTGEN_BINDING=keep, -j 2"
  grep -q "this process may run on (the launcher's binding" "$work/f.txt" || { cat "$work/f.txt"; exit 1; }
  grep -q "^  cores " "$work/f.txt" && { cat "$work/f.txt"; exit 1; }
  # mpirun itself held to one core by taskset: its rank stays there, and the summary warns
  taskset -c 0 "$mpiexec" "${root[@]}" -n 1 -x ROTGEN_BINDING= "$rotgen" sweep "$scene" \
    -o "$work/h" "${vary[@]}" -j 2 >"$work/h.txt" 2>&1
  expect yes "$work/h.txt" "taskset -c 0 mpirun -n 1, -j 2"
  grep -q "^  cores " "$work/h.txt" && { cat "$work/h.txt"; exit 1; }
  # 2 ranks of 2 threads on 2 cores: they share the cores, and the summary says so
  mpi c -n 2 --bind-to core -x ROTGEN_BINDING= -- -j 2
  grep -q "^  warning the 2 ranks on this node run 4 threads on its 2 cores" "$work/c.txt" ||
    (($(nproc) >= 4)) || { cat "$work/c.txt"; exit 1; }
  # ... and so they do unbound, where each rank's threads fit its own cores
  mpi i -n 2 --bind-to none -- -j 2
  grep -q "^  warning the 2 ranks on this node run 4 threads on its 2 cores" "$work/i.txt" ||
    (($(nproc) >= 4)) || { cat "$work/i.txt"; exit 1; }
  mpi d -n 2 --bind-to none -- -j 1
  expect no "$work/d.txt" "mpirun -n 2 --bind-to none, -j 1"
  grep -q "warning" "$work/d.txt" && { cat "$work/d.txt"; exit 1; }
  # one thread on each of 2 ranks bound to a core each: the node's cores together hold them
  mpi j -n 2 --bind-to core -- -j 1
  grep -q "warning" "$work/j.txt" && { cat "$work/j.txt"; exit 1; }
  # a policy it does not know: exit 2, nothing written
  status=0
  ROTGEN_BINDING=spread mpi g -n 1 -x ROTGEN_BINDING -- -j 2 || status=$?
  [[ $status == 2 && ! -e $work/g ]] || { echo "exit $status"; cat "$work/g.txt"; exit 1; }
  grep -q "ROTGEN_BINDING=spread: unknown binding policy" "$work/g.txt" || { cat "$work/g.txt"; exit 1; }
fi
echo "the oversubscription warning appears exactly when the threads outnumber the cores"
