#!/usr/bin/env bash
# The values the README's examples print, from the commands themselves:
#   bash bench/readme/examples.sh build/rotgen > bench/results/readme_examples.md
# 1. The embedding example (README "Embed the kernels in your own CMake project"): its main.cpp,
#    with the kernels of models/heavy_top.yaml from `rotgen emit` (the namespace the model's name
#    where rotgen_add_model would name it top_kernels), compiled against runtime/ and run.
# 2. A run that hits max_steps: models/scenes/heavy_top_nutation.yaml with max_steps: 100, as ms.yaml.
set -euo pipefail
rotgen=$(realpath "${1:-build/rotgen}")
src=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "# The README examples' printed values"
echo
echo "Written by \`bash bench/readme/examples.sh build/rotgen > bench/results/readme_examples.md\`."
echo
"$rotgen" emit "$src/models/heavy_top.yaml" -o "$work" --outputs rhs,jacobian,energy >/dev/null
cat >"$work/main.cpp" <<'CPP'
#include "heavy_top.hpp"
#include <rotgen.hpp>

#include <cstdio>

namespace model = rotgen::models::heavy_top;

int main() {
    const model::params<double> p;
    const double y0[model::state_size] = {0, 0.5, 0, 0, 0, 30};
    double dydt[model::state_size];
    model::rhs(0.0, y0, dydt, p);
    std::printf("theta_ddot(0) = %.6f\n", dydt[4]);
    auto sys = ROTGEN_GENERATED_SYSTEM_WITH_ENERGY(model, double);
    rotgen::state_vector<double, decltype(sys)> y;
    y << 0, 0.5, 0, 0, 0, 30;
    const double e0 = sys.energy(0, y.data());
    const auto result = rotgen::integrate(sys, rotgen::dop853<double>(1e-10, 1e-12), 0.0, y, 10.0);
    if (!result.ok()) return 1;
    std::printf("theta(10) = %.6f, energy drift %.1e\n", y[1], sys.energy(0, y.data()) - e0);
}
CPP
g++ -std=c++17 -O2 -I "$work" -I "$src/runtime" -I /usr/include/eigen3 "$work/main.cpp" -o "$work/mytop"
echo "## The embedding example (models/heavy_top.yaml, DOP853 rtol 1e-10 atol 1e-12 to t = 10)"
echo
echo '```'
"$work/mytop"
echo '```'
echo
echo "## A run that hits max_steps (heavy_top_nutation.yaml with max_steps: 100)"
echo
sed -e "s|model: ../heavy_top.yaml|model: $src/models/heavy_top.yaml|" \
    -e 's|atol: 1e-12}|atol: 1e-12, max_steps: 100}|' \
    "$src/models/scenes/heavy_top_nutation.yaml" >"$work/ms.yaml"
status=0
(cd "$work" && "$rotgen" simulate ms.yaml -q 2>"$work/err") || status=$?
echo '```'
echo "exit status $status"
cat "$work/err"
echo '```'
