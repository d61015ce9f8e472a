#!/usr/bin/env bash
# split2 over 10^7 steps on the heavy top (bench/split/split_bench.cpp, mode `long`): writes
# bench/results/split_long_run.md. One command: bench/split/long_run.sh (about a minute).
set -euo pipefail
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
g++ -O2 -std=c++17 -I runtime -I /usr/include/eigen3 bench/split/split_bench.cpp -o "$work/bench"
"$work/bench" long > "$work/long.txt"
out=bench/results/split_long_run.md
{
  cat <<'MD'
# split2 over 10^7 steps: bounded energy error, p_phi to rounding

`bench/split/long_run.sh`. The heavy top (M g h = 0.981, tilted 0.5 rad, spin 10), split2 with
h = 0.01 from t = 0 to 10^5 (10^7 steps), energy and p_phi sampled every 1000 steps: the largest
relative change from t = 0 within each decade of steps (up to 10^3, 10^3..10^4, ...). A bounded
error stays the same from decade to decade; a drift would grow with them.

| body | steps up to | max abs(E - E0)/E0 | max abs(p_phi - p_phi0)/p_phi0 | run (s) |
|---|---|---|---|---|
MD
  awk '{ printf "| %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5 }' "$work/long.txt"
  echo
  echo "Machine: $(nproc) cores, $(uname -m); $(g++ --version | head -1); $(date -u +%Y-%m-%d)."
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
