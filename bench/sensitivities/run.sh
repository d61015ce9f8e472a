#!/usr/bin/env bash
# The cost of sensitivities (bench/sensitivities/sensitivity_bench.cpp): the variational equations
# against central differences and CVODES, on the heavy top's emitted kernels. From the repository
# root:
#   bash bench/sensitivities/run.sh ROTGEN > bench/results/sensitivities.md
# ROTGEN (default build/rotgen) emits the three headers (k = 1, 4, 6 + 5 keys); the program is
# compiled with g++ -O3 -fno-math-errno (as rotgen compiles kernels), linked statically (so that it
# runs on a machine without SUNDIALS); BENCH_BINARY=FILE only builds it there, and ROWS=FILE makes
# the report from the rows such a binary printed elsewhere (the committed report: rows measured on
# a quiet 16-core machine, as its last line says). The summary is bench/sensitivities/summary.py's:
# at each accuracy of S, the fastest run of each route that reaches it.
set -euo pipefail
rotgen=$(realpath "${1:-build/rotgen}")
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
machine="$(nproc) cores, $(uname -m); $(g++ --version | head -1); load $(cut -d' ' -f1 /proc/loadavg)"
if [[ -n "${ROWS:-}" ]]; then
  cp "$ROWS" "$work/rows"
  machine=${MACHINE:-"measured elsewhere"}
else
emit() { "$rotgen" emit models/heavy_top.yaml -o "$work" --name "$1" --outputs rhs,jacobian \
    --sensitivities "$2" >/dev/null; }
emit heavy_top_k1 parameters.h
emit heavy_top_k4 parameters.h,parameters.I3,parameters.M,parameters.g
emit heavy_top_k11 parameters.I1,parameters.I3,parameters.M,parameters.g,parameters.h
g++ -O3 -fno-math-errno -std=c++17 -static -I "$work" -I runtime -I /usr/include/eigen3 \
    bench/sensitivities/sensitivity_bench.cpp -o "$work/bench" \
    -lsundials_cvodes -lsundials_sunlinsoldense -lsundials_sunmatrixdense -lsundials_nvecserial -lsundials_sunnonlinsolfixedpoint -lm
if [[ -n "${BENCH_BINARY:-}" ]]; then cp "$work/bench" "$BENCH_BINARY"; exit 0; fi
"$work/bench" >"$work/rows"
fi
cat <<MD
# The cost of sensitivities: variational equations, central differences, CVODES

\`bash bench/sensitivities/run.sh build/rotgen\` (bench/sensitivities/sensitivity_bench.cpp). The
heavy top (models/heavy_top.yaml, Lagrangian form), a nutating start (φ, θ, ψ, φ̇, θ̇, ψ̇) = (0.1,
0.5, 0, 0.3, 0.2, 10), t = 0..10, S = ∂y(10)/∂s for the keys s, by three routes on the kernels of
\`rotgen emit --sensitivities\`:

- **variational**: rotgen's DOP853 on \`variational_rhs\` (y and S, n × (n + k): the six initial
  columns are always carried, so k = 1 integrates 6 + 42 values);
- **differences**: central differences of 2k + 1 DOP853 runs of \`rhs\` (the nominal run and two per
  key), step h = rtol^(1/3) · max(1, |s|);
- **cvodes**: SUNDIALS CVODES forward sensitivities (Adams with fixed-point iteration, the non-stiff
  setting of the work-precision bench's CVODE peer, or with Newton, the dense solver and the
  emitted Jacobian, staggered corrector, S in the error test), only the k key columns.

atol = rtol / 100 everywhere. Error of S: the largest |S − S_ref| / max(10⁻³, max |S_ref|) over the
key columns, S_ref from \`variational_rhs\` at rtol 1e-14 (CVODES agrees with it to its own
tolerance: tests/kernels/test_cvodes_sensitivities.cpp). Time: median of 7 runs, wall clock.

## At each accuracy: the fastest run of each route that reaches it

MD
/usr/bin/python3 bench/sensitivities/summary.py "$work/rows"
cat <<MD

## Every run

| keys | route | rtol | ms | error of S |
|---|---|---:|---:|---:|
MD
cat "$work/rows"
echo
echo "Machine: $machine; $(date -u +%Y-%m-%d)."
