#!/usr/bin/env bash
# With a kernel cache local to each node, each node compiles the kernels once, not once a rank:
# rank 0 prepares first, then one rank of every other node, then the rest, who find the kernels
# in their node's cache. Two nodes are played on this machine by the test hook ROTGEN_TEST_NODE
# (the ranks that give the same value form a node) and an MPMD launch that gives each node its
# own ROTGEN_CACHE_DIR: node 0 has rank 0, node 1 ranks 1 and 2. A compiler wrapper logs every
# compilation with the cache it fills; each cache must see as many as the other (2 kernels: the
# heavy top's Lagrangian and body forms), where every rank compiling would give node 1 twice as
# many. summary.csv is one process's.
#   mpi_cache.sh ROTGEN MPIEXEC SOURCE_DIR
set -euo pipefail
rotgen=${1:?rotgen} mpiexec=${2:?mpiexec} src=${3:?source dir}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=$src/models/scenes/heavy_top_nutation.yaml
vary=(--vary initial.theta=0.1:1.5:16)
cat >"$work/cxx.sh" <<'SH'
#!/usr/bin/env bash
[[ " $* " == *" --version "* ]] || echo "$ROTGEN_CACHE_DIR" >>"$COMPILE_LOG"
exec $REAL_CXX "$@"
SH
chmod +x "$work/cxx.sh"
export REAL_CXX=${CXX:-c++} COMPILE_LOG=$work/compilations CXX=$work/cxx.sh
ROTGEN_CACHE_DIR=$work/one_cache "$rotgen" sweep "$scene" -o "$work/one" "${vary[@]}" -j 1 -q
root=()
[[ $(id -u) == 0 ]] && root=(--allow-run-as-root)
rm -f "$COMPILE_LOG"
node() { # node K RANKS: an app context of RANKS ranks that play node K, with its own cache
  printf '%s ' -n "$2" -x ROTGEN_TEST_NODE="$1" -x ROTGEN_CACHE_DIR="$work/cache$1" "$rotgen" \
    sweep "$scene" -o "$work/ranks" "${vary[@]}" -j 1 -q
}
# shellcheck disable=SC2046 # the words of each app context
"$mpiexec" "${root[@]}" --oversubscribe $(node 0 1) : $(node 1 2)
cmp "$work/one/summary.csv" "$work/ranks/summary.csv"
on0=$(grep -cx "$work/cache0" "$COMPILE_LOG" || true)
on1=$(grep -cx "$work/cache1" "$COMPILE_LOG" || true)
[[ $on0 == 2 && $on1 == 2 ]] || {
  echo "compilations: $on0 into node 0's cache, $on1 into node 1's (expected 2 and 2)"
  exit 1
}
echo "each node compiled the 2 kernels once into its own cache; summary.csv is one process's"
