#!/usr/bin/env bash
# What lanes can gain in a Taylor expansion (Markdown on stdout, progress on stderr):
#
#   bash bench/lanes/taylor_kernel.sh build/rotgen > bench/results/taylor_kernel.md
#
# The heavy top's taylor_fixed<15> (the expansion of bench/lanes/taylor_lanes.sh's sweep at rtol
# 1e-12), emitted by ROTGEN, timed per member on double, on one AVX2 batch of 4 doubles and on two
# batches interleaved (bench/lanes/taylor_kernel.cpp), each compiled as rotgen compiles it: double
# as a `taylor` scene's scalar kernels (-O3 -mavx2; and without it, as before), the batches as the
# lane kernels (-O3 -mavx2 -mfma -ffp-contract=fast: products fused into sums). COPIES (default 7)
# fresh copies of each program run once each (a copy's speed depends on where its pages lie in
# memory on a virtual machine); the medians.
set -euo pipefail
rotgen=$(realpath "${1:?usage: taylor_kernel.sh ROTGEN}")
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
copies=${COPIES:-7}
"$rotgen" emit models/heavy_top.yaml -o "$work" --outputs rhs,taylor --name bench_heavy_top >/dev/null
build() { # OUT FLAGS...
  local out=$1
  shift
  g++ -std=c++17 -O3 -fno-math-errno -DNDEBUG "$@" -DUNIT=bench_heavy_top \
      -DUNIT_HEADER="\"$work/bench_heavy_top.hpp\"" bench/lanes/taylor_kernel.cpp -o "$out"
}
build "$work/portable"
build "$work/scalar" -mavx2
build "$work/lanes" -mavx2 -mfma -ffp-contract=fast
wide=no # the 8-wide batches of a `taylor` scene's lane kernels where the CPU has AVX-512
if grep -q ' avx512f ' /proc/cpuinfo && grep -q ' avx512dq ' /proc/cpuinfo; then
  wide=yes
  build "$work/wide" -mavx512f -mavx512dq -mavx512vl -mavx512bw -mavx2 -mfma -ffp-contract=fast
fi
for ((i = 0; i < copies; i++)); do
  echo "copy $((i + 1)) of $copies" >&2
  cp "$work/scalar" "$work/s$i" && cp "$work/lanes" "$work/l$i" && cp "$work/portable" "$work/p$i"
  read -r s _ _ < <("$work/s$i")
  read -r _ b t < <("$work/l$i")
  read -r p _ _ < <("$work/p$i")
  b8=-
  if [ $wide = yes ]; then
    cp "$work/wide" "$work/w$i" && read -r _ b8 _ < <("$work/w$i") && rm "$work/w$i"
  fi
  echo "$s $b $t $p $b8" >>"$work/times"
  rm "$work/s$i" "$work/l$i" "$work/p$i"
done
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
col() { awk -v c="$1" '{ print $c }' "$work/times" | median; }
s=$(col 1) b=$(col 2) t=$(col 3) p=$(col 4) b8=$(col 5)
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
cat <<MD
# What lanes gain in one Taylor expansion

\`bash bench/lanes/taylor_kernel.sh build/rotgen > bench/results/taylor_kernel.md\`; $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //'),
$(g++ --version | head -1), load average $(cut -d' ' -f1-3 /proc/loadavg) when it finished.

The heavy top's \`taylor_fixed<15>\` (its sweep's order at rtol 1e-12), one expansion per member,
ns per member: the median over $copies fresh copies of each program (each copy's time the median of
15 timings). The scalar expansion is compiled as a \`taylor\` scene's kernels are (\`-mavx2\`:
the sums of the recurrences run four terms to a vector), the batches as the lane kernels are (with FMA, products fused into sums).

| expansion | ns per member | speed-up over double |
|---|---:|---:|
| double (one member, as without \`--lanes\`) | $s | 1 |
| double, compiled without \`-mavx2\` (as a sweep's scalar kernels were before) | $p | $(ratio "$s" "$p") |
| one batch of 4 lanes (\`--lanes 4\`; \`--lanes 8\` calls it twice) | $b | $(ratio "$s" "$b") |
| two batches of 4 interleaved in one expansion (8 lanes) | $t | $(ratio "$s" "$t") |
$([ $wide = yes ] && echo "| one batch of 8 lanes on AVX-512 (a \`taylor\` scene's \`--lanes 8\` there) | $b8 | $(ratio "$s" "$b8") |")

Every copy's "double, batch, two batches, double without -mavx2, AVX-512 batch" ns: $(tr '\n' ';' <"$work/times" | sed 's/;$//; s/;/; /g').
MD
