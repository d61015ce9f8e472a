#!/usr/bin/env bash
# The size of the 3D viewer page (rotgen simulate --view) against the number of samples: the heavy
# top of models/scenes/heavy_top_nutation.yaml with 101 to 100,001 samples.
#   bash bench/view_size.sh [build/rotgen] > bench/results/view.md
set -euo pipefail
rotgen=$(realpath "${1:-build/rotgen}")
src=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "# The viewer page's size"
echo
echo "\`bash bench/view_size.sh\`: \`rotgen simulate --view\` on the nutating heavy top (7 recorded"
echo "columns, the attitude added for the page; the attitude and t to 17 digits, the read-out values to 9), t = 0..10."
echo
echo "| samples | page bytes | MB |"
echo "|---:|---:|---:|"
for n in 101 1001 10001 100001; do
  sed "s/samples: 1001/samples: $n/; s|model: ../heavy_top.yaml|model: $src/models/heavy_top.yaml|" \
    "$src/models/scenes/heavy_top_nutation.yaml" > "$work/scene.yaml"
  "$rotgen" simulate "$work/scene.yaml" -o "$work/run.csv" --view "$work/run.html" -q
  bytes=$(stat -c %s "$work/run.html")
  printf '| %s | %s | %.2f |\n' "$n" "$bytes" "$(echo "$bytes / 1000000" | bc -l)"
done
