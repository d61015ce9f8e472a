#!/usr/bin/env bash
# A sweep under `mpirun -n 2` writes the same files, byte for byte, as one process with one
# thread: summary.csv (with a failed member and an event column) and trajectories.h5.
#   mpi_sweep.sh ROTGEN MPIEXEC SOURCE_DIR
set -euo pipefail
rotgen=${1:?rotgen} mpiexec=${2:?mpiexec} src=${3:?source dir}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat >"$work/scene.yaml" <<YAML
model: $src/models/heavy_top.yaml
initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}
time: {end: 2, samples: 101}
integrator: {method: dop853, rtol: 1e-10, atol: 1e-12, max_steps: 300}
record: [theta, energy, body_z]
events:
  - {name: turn, when: theta_dot, direction: falling}
sweep:
  vary:
    initial.theta: {from: 0.2, to: 1.4, count: 7}
    initial.psi_dot: {values: [5, 30, 2000]}
YAML
status=0
"$rotgen" sweep "$work/scene.yaml" -o "$work/one" -j 1 --trajectories -q || status=$?
[[ $status == 3 ]] || { echo "one process: exit $status, expected 3 (the psi_dot 2000 members)"; exit 1; }
root=()
[[ $(id -u) == 0 ]] && root=(--allow-run-as-root)
status=0
"$mpiexec" -n 2 --oversubscribe "${root[@]}" "$rotgen" sweep "$work/scene.yaml" -o "$work/two" \
  --trajectories -q || status=$?
[[ $status == 3 ]] || { echo "mpirun -n 2: exit $status, expected 3"; exit 1; }
for f in summary.csv trajectories.h5; do
  cmp "$work/one/$f" "$work/two/$f" || { echo "$f differs between 1 process and 2 ranks"; exit 1; }
done
head -1 "$work/one/summary.csv" | grep -q ',event.turn,drift.energy,' ||
  { echo "summary.csv has no event.turn column"; exit 1; }
rows=$(($(wc -l <"$work/one/summary.csv") - 1))
[[ $rows == 21 ]] || { echo "summary.csv has $rows members, expected 21"; exit 1; }
echo "2 ranks wrote the same summary.csv and trajectories.h5 as 1 process ($rows members)"
