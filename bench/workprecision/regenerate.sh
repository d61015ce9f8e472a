#!/usr/bin/env bash
# Regenerates the work-precision reports of the shipped scenes and the README's plots:
#   bench/workprecision/regenerate.sh [path/to/rotgen]
# Each scene: bench-out/<scene>/{results.csv,results.md,final_states.csv,drift.csv,*.png}; the plots
# are copied to docs/work_precision_<scene>_{time,evals,drift}.png and the report to
# bench/results/workprecision_<scene>.md (the tables behind the plots). Not run by the tests (timings
# belong in benchmarks); takes ~1 minute per scene with the driver cached, ~2-3 minutes cold.
set -euo pipefail
cd "$(dirname "$0")/../.."
rotgen=${1:-build/rotgen}
for scene in free_top_workprecision heavy_top_nutation; do
  "$rotgen" bench "models/scenes/$scene.yaml" -o "bench-out/$scene"
  cp "bench-out/$scene/work_precision_time.png" "docs/work_precision_${scene}_time.png"
  cp "bench-out/$scene/work_precision_evals.png" "docs/work_precision_${scene}_evals.png"
  cp "bench-out/$scene/invariant_drift.png" "docs/work_precision_${scene}_drift.png"
  cp "bench-out/$scene/results.md" "bench/results/workprecision_$scene.md"
done
