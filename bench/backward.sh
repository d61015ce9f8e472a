#!/usr/bin/env bash
# A heavy top run forward t = 0 -> 2 and back 2 -> 0 (`time: {start: 2, end: 0}`, continued from
# the forward run's last row with --from): how far the state comes back from its start, the
# largest difference over the recorded state columns, for DOP853 at rtol 1e-13 (Lagrangian form)
# and the split methods at a fixed step 0.01 (200 steps each way; body form).
#   bash bench/backward.sh build/rotgen > bench/results/backward.md
set -euo pipefail
rotgen=$(realpath "${1:-build/rotgen}")
src=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "# There and back: a heavy top run forward and backward in time"
echo
echo "Written by \`bash bench/backward.sh build/rotgen > bench/results/backward.md\`: models/heavy_top.yaml"
echo "from phi 0.3, theta 0.5, psi 0.2, phi_dot 1, theta_dot 0.4, psi_dot 30, t = 0 -> 2 -> 0."
echo
echo "| form | integrator | max over the state of abs(back(0) - start) |"
echo "|---|---|---|"
run() { # form, integrator, record
    local scene="$work/top.yaml"
    printf 'model: %s\nform: %s\ninitial: {phi: 0.3, theta: 0.5, psi: 0.2, phi_dot: 1, theta_dot: 0.4, psi_dot: 30}\nintegrator: %s\nrecord: %s\n' \
        "$src/models/heavy_top.yaml" "$1" "$2" "$3" >"$scene"
    cp "$scene" "$work/there.yaml" && echo "time: {start: 0, end: 2, samples: 11}" >>"$work/there.yaml"
    cp "$scene" "$work/back.yaml" && echo "time: {start: 2, end: 0, samples: 11}" >>"$work/back.yaml"
    "$rotgen" simulate "$work/there.yaml" -o "$work/there.csv" -q
    "$rotgen" simulate "$work/back.yaml" -o "$work/back.csv" --from "$work/there.csv" -q
    local worst
    # (each CSV: a "# rotgen ..." line, the header, then the rows)
    worst=$(awk -F, '/^#/ { next }
                     NR == FNR { if (++rows == 2) for (i = 2; i <= NF; ++i) s[i] = $i; next }
                     { last = $0 }
                     END { n = split(last, b, ","); w = 0
                           for (i = 2; i <= n; ++i) { d = b[i] - s[i]; if (d < 0) d = -d; if (d > w) w = d }
                           printf "%.1e", w }' "$work/there.csv" "$work/back.csv")
    echo "| $1 | \`$2\` | $worst |"
}
run lagrangian "{method: dop853, rtol: 1e-13, atol: 1e-13}" "[phi, theta, psi, phi_dot, theta_dot, psi_dot]"
run body "{method: split4, step: 0.01}" "[q0, q1, q2, q3, omega1, omega2, omega3]"
run body "{method: split2, step: 0.01}" "[q0, q1, q2, q3, omega1, omega2, omega3]"
