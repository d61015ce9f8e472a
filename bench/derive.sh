#!/usr/bin/env bash
# rotgen — derivation benchmark against SymPy, in one command:
#
#   bench/derive.sh [--route structured|legendre|both] [MODEL...]
#
# Builds derive_bench if needed (in $ROTGEN_BUILD_DIR, default <repo>/build; -j2), times rotgen's
# load_model + derive (bench/derive_bench.cpp: median of 9 repeats, each >= 0.2 s) and SymPy's
# LagrangesMethod + solve for q_ddot + Hamiltonian + Hamilton's equations (bench/derive_sympy.py:
# median of 3 repeats, cold cache) for each model (default: heavy_top full_tensor_top), and prints
# a Markdown table per SymPy route:
#   structured  H = 1/2 l^T I^-1 l + V with l = J^-T p, the algorithm rotgen itself uses;
#   legendre    H = p.q_dot - L with q_dot = M^-1 p by an LU solve, the textbook route.
# Progress goes to stderr; stdout is only the tables. Timing claims live here, never in ctest.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(dirname "$here")
build=${ROTGEN_BUILD_DIR:-$root/build}
python=${ROTGEN_PYTHON:-/usr/bin/python3} # Debian's interpreter: python3-sympy, python3-yaml

route=both
models=()
while [ $# -gt 0 ]; do
    case $1 in
        --route) route=${2:?--route needs structured, legendre or both}; shift 2 ;;
        --route=*) route=${1#--route=}; shift ;;
        -h|--help) sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        -*) echo "derive.sh: error: unknown option '$1'" >&2; exit 2 ;;
        *) models+=("$1"); shift ;;
    esac
done
case $route in
    structured) routes=(structured) ;;
    legendre) routes=(legendre) ;;
    both) routes=(structured legendre) ;;
    *) echo "derive.sh: error: --route must be structured, legendre or both" >&2; exit 2 ;;
esac
[ ${#models[@]} -gt 0 ] || models=(heavy_top full_tensor_top)
files=()
for m in "${models[@]}"; do
    f=$m
    [ -f "$f" ] || f=$root/models/$m.yaml
    [ -f "$f" ] || { echo "derive.sh: error: no model file '$m' (nor $f)" >&2; exit 2; }
    files+=("$f")
done

# Build (configure first if the tree is new, or configured before bench/ existed).
if [ ! -f "$build/CMakeCache.txt" ]; then
    cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >&2
fi
if ! cmake --build "$build" -j2 --target derive_bench >&2; then
    echo "derive.sh: reconfiguring $build and building again" >&2
    cmake -S "$root" -B "$build" >&2
    cmake --build "$build" -j2 --target derive_bench >&2
fi

echo "derive.sh: timing rotgen (load_model + derive) ..." >&2
rotgen_tsv=$("$build/bench/derive_bench" --format tsv "${files[@]}")

for r in "${routes[@]}"; do
    echo "derive.sh: timing SymPy ($r route; several seconds per model) ..." >&2
    sympy_tsv=$("$python" "$here/derive_sympy.py" --format tsv --hamiltonian "$r" "${files[@]}")
    echo
    echo "SymPy $("$python" -c 'import sympy; print(sympy.__version__)') route: $r" \
         "(rotgen: median of 9 repeats; SymPy: median of 3, cold cache)"
    echo
    echo "| model | rotgen median (ms) | SymPy median (s) | ratio |"
    echo "|---|---:|---:|---:|"
    # Join on the model name: rotgen's median (s) and SymPy's median (s).
    awk -F'\t' 'NR == FNR { rotgen[$1] = $2; order[++n] = $1; next }
                { sympy[$1] = $2 }
                END {
                    for (i = 1; i <= n; ++i) {
                        m = order[i]
                        printf "| %s | %.3f | %.3f | %.0f× |\n", m, rotgen[m] * 1e3, sympy[m], sympy[m] / rotgen[m]
                    }
                }' <(printf '%s\n' "$rotgen_tsv") <(printf '%s\n' "$sympy_tsv")
done
