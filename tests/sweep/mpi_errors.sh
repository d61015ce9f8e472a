#!/usr/bin/env bash
# When a rank other than 0 cannot prepare the scene (a node without the scene file, or without a
# working compiler), rank 0 reports that rank's own error, naming the rank and its host, in one
# line: exit 2 for bad input (the scene file), 1 for the machine (the compiler); nothing written.
# An MPMD launch gives rank 1 its own arguments or environment. Rank 0 is held 2 s before it
# prints (the hook ROTGEN_TEST_PAUSE) while rank 1 exits: mpirun must have no failed rank to end
# rank 0 for before it has said why (a rank 1 that exited 1 had it ended with SIGTERM, the error
# unsaid, the interrupt line naming a journal stamp already removed).
#   mpi_errors.sh ROTGEN MPIEXEC SOURCE_DIR
set -euo pipefail
rotgen=${1:?rotgen} mpiexec=${2:?mpiexec} src=${3:?source dir}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=$src/models/scenes/heavy_top_nutation.yaml
vary=(--vary initial.theta=0.1:1.5:4)
root=()
[[ $(id -u) == 0 ]] && root=(--allow-run-as-root)
run() { # run NAME RANK0_WORDS... : RANK1_WORDS...: exit status in $status, stderr in NAME.txt
  local name=$1
  shift
  status=0
  "$mpiexec" "${root[@]}" --oversubscribe "$@" 2>"$work/$name.txt" >/dev/null || status=$?
}
check() { # check NAME STATUS TEXT: the status, one rotgen line holding TEXT, and no output folder
  local lines
  lines=$(grep -c '^rotgen: ' "$work/$1.txt" || true)
  [[ $status == "$2" && $lines == 1 && ! -e $work/out ]] && grep -qF "$3" "$work/$1.txt" || {
    echo "$1: exit $status (expected $2), $lines rotgen lines, out $(ls -d "$work/out" 2>&1):"
    cat "$work/$1.txt"
    exit 1
  }
}
sweep=(sweep -o "$work/out" "${vary[@]}" -j 1 -q)
run missing -n 1 "$rotgen" "${sweep[@]}" "$scene" : -n 1 "$rotgen" "${sweep[@]}" "$work/elsewhere.yaml"
check missing 2 "rotgen: error: $work/elsewhere.yaml: cannot open file: No such file or directory (MPI rank 1 on "
run compiler -n 1 -x ROTGEN_CACHE_DIR="$work/c0" -x ROTGEN_TEST_PAUSE=report:2 "$rotgen" "${sweep[@]}" "$scene" \
  : -n 1 -x ROTGEN_CACHE_DIR="$work/c1" -x CXX=/nonexistent/c++ "$rotgen" "${sweep[@]}" "$scene"
check compiler 1 "rotgen: internal error: no working C++ compiler ('/nonexistent/c++')"
grep -qF "(MPI rank 1 on " "$work/compiler.txt" || { cat "$work/compiler.txt"; exit 1; }
echo "rank 0 reports another rank's error, naming it, with that error's exit status"
