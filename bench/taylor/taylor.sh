#!/usr/bin/env bash
# The Taylor method against DOP853: time to reach an error on the free top and the heavy top,
# t = 0..100, with the checked-in generated headers and the runtime (see taylor_bench.cpp).
#   bash bench/taylor/taylor.sh > bench/results/taylor.md
set -euo pipefail
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
g++ -O2 -std=c++17 -I generated -I runtime -I /usr/include/eigen3 bench/taylor/taylor_bench.cpp \
  -o "$work/taylor_bench"
echo "# The Taylor method against DOP853 (\`bash bench/taylor/taylor.sh\`)"
echo
echo "Wall time of one run t = 0..100 (median of 7 loops), compiled with g++ -O2; rtol = atol = tol."
echo "Each method's time to an error is its fastest run, over a sweep of tolerances in half"
echo "decades, whose error at t = 100 is at most that. Taylor's order is ceil(-ln(tol)/2 + 1)"
echo "(Jorba-Zou); its step follows from the last two coefficients."
echo
"$work/taylor_bench"
