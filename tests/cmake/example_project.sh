#!/usr/bin/env bash
# Installs rotgen from BUILD_DIR into a scratch prefix, then configures, builds and runs the
# separate project examples/embed against it (find_package(rotgen), rotgen_add_model()).
# Then edits the model and checks that the next build regenerates the kernels.
#   example_project.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cp -r "$src/examples/embed" "$work/embed"
# the runtime target asks its users for C++17 (GCC 12 defaults to it; other compilers may not)
grep -rq "INTERFACE_COMPILE_FEATURES \"cxx_std_17\"" "$work/prefix" --include='rotgenTargets*.cmake' ||
    { echo "rotgen::runtime does not carry cxx_std_17"; exit 1; }
cmake -S "$work/embed" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/gyroscope"
header=$(find "$work/build" -name gyroscope_kernels.hpp)
grep -q "T M = T(rg_scalar(1)/rg_scalar(2));" "$header" || { echo "unexpected default of M in $header"; exit 1; }
# An edited model must regenerate the header on the next build.
sed -i 's/M: {value: 0.5,/M: {value: 0.7,/' "$work/embed/gyroscope.yaml"
cmake --build "$work/build" >/dev/null
grep -q "T M = T(rg_scalar(7)/rg_scalar(10));" "$header" || { echo "the header was not regenerated after the model changed"; exit 1; }
# Without FORM, emit's own default: a linear rotor gets its rotor form (passing `--form
# lagrangian` stops the build); SENSITIVITIES reaches `emit --sensitivities`.
cp "$src/models/dumbbell.yaml" "$work/embed/dumbbell.yaml"
printf '#include "dumbbell_kernels.hpp"\n#include "sensitive_kernels.hpp"\nint main() {}\n' \
    >"$work/embed/more.cpp"
cat >>"$work/embed/CMakeLists.txt" <<'CMAKE'
rotgen_add_model(dumbbell_kernels MODEL dumbbell.yaml)
rotgen_add_model(sensitive_kernels MODEL gyroscope.yaml SENSITIVITIES parameters.l parameters.I3)
add_executable(more more.cpp)
target_link_libraries(more PRIVATE dumbbell_kernels sensitive_kernels rotgen::runtime)
target_compile_options(more PRIVATE -Wall -Wextra -Wpedantic -Werror)
CMAKE
cmake "$work/build" >/dev/null
cmake --build "$work/build" --target more >/dev/null ||
    { echo "a rotor model without FORM, or SENSITIVITIES, did not build"; exit 1; }
grep -q "form rotor" "$(find "$work/build" -name dumbbell_kernels.hpp)" ||
    { echo "the rotor model was not emitted in its rotor form"; exit 1; }
grep -q "sensitivity_count = 2" "$(find "$work/build" -name sensitive_kernels.hpp)" ||
    { echo "SENSITIVITIES did not reach the header"; exit 1; }
# The installed `rotgen bench` finds its harness and runtime in the prefix, not in the source tree.
out=$(cd "$work" && "$work/prefix/bin/rotgen" bench "$src/models/scenes/free_top_workprecision.yaml" \
      -o "$work/bench" --quick --long-steps 0)
grep -q "harness   $work/prefix/share/rotgen/bench/workprecision, runtime $work/prefix/include/rotgen/runtime" \
    <<<"$out" || { echo "the installed rotgen bench did not use the installed harness:"; echo "$out"; exit 1; }
test -s "$work/bench/results.csv" || { echo "the installed rotgen bench wrote no results.csv"; exit 1; }
echo "example project: built, ran, and regenerated after a model change; a rotor model without FORM and SENSITIVITIES built; installed bench ran"
