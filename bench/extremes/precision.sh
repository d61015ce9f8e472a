#!/usr/bin/env bash
# Precision: float vs double vs long double on the same scene, with the checked-in generated
# kernels and the runtime (no `rotgen simulate`: it runs in double only). See precision.cpp.
#   bench/extremes/precision.sh
# The float/double/long double work-precision comparison (cost against accuracy) is
# `rotgen bench` (bench/workprecision/); this table shows only where each type's rounding
# takes over from the integrator's truncation error.
set -euo pipefail
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
g++ -O2 -std=c++17 -I generated -I runtime -I /usr/include/eigen3 bench/extremes/precision.cpp -o "$work/precision"
echo "| integrator | float | double | long double |"
echo "|---|---:|---:|---:|"
"$work/precision"
echo
echo "max |omega - exact| over t in [0, 100] (max |E(t)/E(0) - 1|); free asymmetric top I = (1, 2, 3),"
echo "omega(0) = (1, 0.1, 0.5), body form; exact: Jacobi elliptic functions in long double"
