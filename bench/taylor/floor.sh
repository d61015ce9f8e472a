#!/usr/bin/env bash
# The Taylor method's accuracy floor on the free top as a distribution over 40 nearby initial
# states (bench/taylor/floor.cpp), for this checkout's runtime and generated headers, and for each
# other checkout (a git worktree of an older commit, say) given:
#   bash bench/taylor/floor.sh [OTHER_ROOT...] > bench/results/taylor_floor.md
set -euo pipefail
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "# The Taylor method's accuracy floor on the free top"
echo
echo "\`bash bench/taylor/floor.sh${*:+ $*}\`: the error at t = 100 (max-norm, against the exact"
echo "solution in long double) over 400 initial states omega0 + (1e-3 i, 1e-3 j, 1e-4 l), i < 7, j < 5, l < 58,"
echo "I = (1, 2, 3), compiled as rotgen compiles kernels (g++ -O3, AVX2, -ffp-contract=off)."
for root in "$PWD" "$@"; do
  root=$(realpath "$root")
  g++ -std=c++17 -O3 -fno-math-errno -DNDEBUG -mavx2 -mfma -ffp-contract=off \
    -I "$root/generated" -I "$root/runtime" -I /usr/include/eigen3 bench/taylor/floor.cpp \
    -o "$work/floor"
  echo
  echo "### $(git -C "$root" log -1 --format='%h %s' | cut -c1-90)"
  echo
  echo "| tol | least | median | 90th percentile | largest | within 3e-15 |"
  echo "|---|---:|---:|---:|---:|---:|"
  "$work/floor"
done
