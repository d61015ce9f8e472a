#!/usr/bin/env bash
# The rhs of every shipped model before and after hoisting the parameter-only subexpressions
# (prepared<T>): writes bench/results/hoist.md. From the repository root:
#   bash bench/kernels/hoist.sh NEW_ROTGEN OLD_ROTGEN [ROUNDS]
# OLD_ROTGEN is a build from before the change (its rhs takes params<T>). Each model's rhs is
# emitted by both (default form: lagrangian, the body form for the free asymmetric top and the
# full tensor top as well) into one program, compiled with g++ -O3 -fno-math-errno (the flags
# rotgen compiles its kernels with), and timed over 256 random
# states: ns per call (CPU time of the thread), the median of ROUNDS (default 15) interleaved
# rounds; "after" passes prepare(p) made once, "after, params" passes params<T> (prepared at each
# call). Both sides are checked to agree (relative 1e-13) before timing.
set -euo pipefail
new=$(realpath "$1") old=$(realpath "$2") rounds=${3:-15}
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
units=()
emit() { # model form unit
  "$old" emit "models/$1.yaml" -o "$work" --form "$2" --outputs rhs --name "$3_before" >/dev/null
  "$new" emit "models/$1.yaml" -o "$work" --form "$2" --outputs rhs --name "$3_after" >/dev/null
  units+=("$3")
}
for m in heavy_top damped_driven_top free_asymmetric_top full_tensor_top cube_on_corner satellite_zyx; do
  emit "$m" lagrangian "$m"
done
emit free_asymmetric_top body free_asymmetric_top_body
emit full_tensor_top body full_tensor_top_body
emit dumbbell rotor dumbbell_rotor
{
  echo '#include "bench/kernels/hoist_driver.hpp"'
  for u in "${units[@]}"; do echo "#include \"${u}_before.hpp\""; echo "#include \"${u}_after.hpp\""; done
  echo 'int main() {'
  echo '    std::vector<row> rows;'
  echo "    rows.reserve(${#units[@]});"
  for u in "${units[@]}"; do
    echo "    rows.push_back(make_row(\"$u\", rotgen::models::${u}_before::state_size));"
    echo "    ROTGEN_HOIST_TIMERS(rows.back(), $u);"
  done
  echo "    report(rows, $rounds);"
  echo '}'
} > "$work/main.cpp"
g++ -O3 -fno-math-errno -std=c++17 -I . -I "$work" "$work/main.cpp" -o "$work/bench"
out=bench/results/hoist.md
{
  cat <<MD
# Parameter-only subexpressions hoisted out of the rhs (prepared<T>)

\`bash bench/kernels/hoist.sh build/rotgen OLD/build/rotgen\` (bench/kernels/hoist_driver.hpp).
Each model's rhs as emitted before the change (params<T>) and after it (prepared<T>, made once by
prepare(p)); ns per call, CPU time of the thread, over 256 random states, the median of $rounds
interleaved rounds, compiled together with g++ -O3 -fno-math-errno (as rotgen compiles kernels).
"ops": + - * / and calls per call, from the headers' comments, and the constants' operations done once in prepare(). Ratio: after / before
(< 1: faster).

MD
  "$work/bench"
  echo
  echo "| rhs | ops before | ops after | constants in prepare() | their ops |"
  echo "|---|---:|---:|---:|---:|"
  for u in "${units[@]}"; do
    ops() { grep -m1 '^//   rhs: ' "$1" | sed 's/.*-> \([0-9]*\).*/\1/'; }
    count=$(grep -o 'computed from them once, the [0-9]*' "$work/${u}_after.hpp" | grep -o '[0-9]*$')
    cops=$(grep -o '^// rhs, jacobian and rhs_and_jacobian use ([0-9]*' "$work/${u}_after.hpp" | grep -o '[0-9]*$')
    echo "| $u | $(ops "$work/${u}_before.hpp") | $(ops "$work/${u}_after.hpp") | $count | $cops |"
  done
  echo
  echo "Machine: $(nproc) cores, $(uname -m); $(g++ --version | head -1); load $(cut -d' ' -f1 /proc/loadavg); $(date -u +%Y-%m-%d)."
} > "$out.tmp"
mv "$out.tmp" "$out"
cat "$out"
