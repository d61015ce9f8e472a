#!/usr/bin/env bash
# Regenerates the checked-in headers of the shipped models (run from anywhere):
#   generated/regenerate.sh [path/to/rotgen]
# Every form a model has; the reduced form only where the model has a cyclic coordinate.
set -euo pipefail
cd "$(dirname "$0")/.."
rotgen=${1:-build/rotgen}
for model in heavy_top free_asymmetric_top full_tensor_top damped_driven_top cube_on_corner; do
  for form in lagrangian hamiltonian body reduced; do
    if [ "$form" = reduced ] && [ "$model" = damped_driven_top ]; then continue; fi
    "$rotgen" emit "models/$model.yaml" -o generated --form "$form" >/dev/null
  done
done
# A model in yaw, pitch, roll (z-y-x angles, issue 28): its Euler-angle and body forms.
for form in lagrangian body; do
  "$rotgen" emit models/satellite_zyx.yaml -o generated --form "$form" >/dev/null
done
# Examples of the Taylor coefficients (--outputs taylor), readable beside the rhs they expand.
"$rotgen" emit models/free_asymmetric_top.yaml -o generated --form body --outputs rhs,taylor \
  --name free_asymmetric_top_body_taylor >/dev/null
"$rotgen" emit models/heavy_top.yaml -o generated --outputs rhs,energy,momenta,taylor \
  --name heavy_top_taylor >/dev/null
ls generated/*.hpp
