# Sourced by the bench scripts: the heavy-top ensemble they share (models/heavy_top.yaml, initial
# theta 0.1 .. 1.5, t = 0 .. 10, 101 samples, theta and the energy recorded).
#   heavy_top_sweep FILE MEMBERS INTEGRATOR     e.g. "{method: dop853, rtol: 1e-8, atol: 1e-10}"
heavy_top_sweep() {
  local models
  models=$(cd "$(dirname "${BASH_SOURCE[0]}")/../models" && pwd)
  cat >"$1" <<YAML
model: $models/heavy_top.yaml
initial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}
time: {start: 0, end: 10, samples: 101}
integrator: $3
record: [theta, energy]
sweep:
  vary:
    initial.theta: {from: 0.1, to: 1.5, count: $2}
YAML
}
