#!/usr/bin/env bash
# Where the heavy top's rhs spends its time (its sine-cosine pair against its arithmetic), which
# bounds what hoisting parameter-only subexpressions can gain: writes bench/results/rhs_share.md.
# From the repository root:
#   bash bench/kernels/rhs_share.sh [COPIES]
# Compiled with g++ -O3 -fno-math-errno (as rotgen compiles kernels); each of COPIES (default 5)
# fresh copies of the program is run once (a copy's speed depends on where its pages lie in memory
# on a virtual machine), and the table is the copy with the median rhs time.
set -euo pipefail
copies=${1:-5}
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
g++ -O3 -fno-math-errno -std=c++17 -I . bench/kernels/rhs_share.cpp -o "$work/bench"
for ((i = 0; i < copies; i++)); do
  cp "$work/bench" "$work/copy$i"
  "$work/copy$i" >"$work/table$i"
done
median_table=$(for ((i = 0; i < copies; i++)); do
  echo "$(awk -F'|' 'NR == 1 { print $3 + 0 }' "$work/table$i") $i"
done | sort -g | awk -v n="$copies" 'NR == int((n + 1) / 2) { print $2 }')
out=bench/results/rhs_share.md
{
  cat <<MD
# The heavy top's rhs: its sine and cosine against its arithmetic

\`bash bench/kernels/rhs_share.sh\` (bench/kernels/rhs_share.cpp). generated/heavy_top.hpp's rhs
with prepared parameters; its sin(theta), cos(theta) alone (one call of glibc's sincos, as in the rhs); its statements with
the sine and cosine given (checked to give the rhs's bits at every state). ns per call, CPU time
of the thread, over 256 random states, the median of 21 interleaved rounds; of $copies fresh
copies of the program, the one with the median rhs time. Hoisting took 5 of its 33 operations
into prepare() (bench/results/hoist.md); what is left for any change to the arithmetic is its
share below.

| part | ns per call | share of the rhs |
|---|---:|---:|
MD
  cat "$work/table$median_table"
  echo
  echo "All copies' rhs times (ns): $(for ((i = 0; i < copies; i++)); do awk -F'|' 'NR == 1 { printf "%s ", $3 + 0 }' "$work/table$i"; done)"
  echo
  echo "Machine: $(nproc) cores, $(uname -m); $(g++ --version | head -1); load $(cut -d' ' -f1 /proc/loadavg); $(date -u +%Y-%m-%d)."
} >"$out.tmp"
mv "$out.tmp" "$out"
cat "$out"
