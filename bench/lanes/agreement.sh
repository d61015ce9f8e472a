#!/usr/bin/env bash
# How closely `rotgen sweep --lanes` agrees with the same sweep without lanes: the largest
# relative difference over the members of the summary's final.* columns and event.* columns
# (the events' first times), and the digits that agree (floor of -log10 of it). The sweeps are
# those of tests/sweep/test_sweep_lanes.cpp: 20 heavy tops (theta0 0.2 .. 1.4, h 0.1 and 0.3) to
# t = 2 in lanes of 4, and 8 falling tops (psi_dot 0 .. 10, events halfway and floor) in lanes of 8.
#   bash bench/lanes/agreement.sh build/rotgen > bench/results/lanes_agreement.md
set -euo pipefail
rotgen=$(realpath "${1:-build/rotgen}")
src=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
top() { # integrator
    printf 'model: %s\ninitial: {phi: 0, theta: 0.5, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 30}\ntime: {end: 2, samples: 41}\nintegrator: %s\nrecord: [theta, phi, energy, p_phi]\nsweep:\n  vary:\n    initial.theta: {from: 0.2, to: 1.4, count: 10}\n    parameters.h: {values: [0.1, 0.3]}\n' \
        "$src/models/heavy_top.yaml" "$1"
}
falling() { # integrator
    printf 'model: %s\ninitial: {phi: 0, theta: 0.3, psi: 0, phi_dot: 0, theta_dot: 0, psi_dot: 0}\ntime: {end: 5, samples: 51}\nintegrator: %s\nrecord: [theta, theta_dot, energy]\nevents:\n  - {name: halfway, when: theta - pi/4, direction: rising}\n  - {name: floor, when: theta - pi/2, direction: rising, action: stop}\nsweep:\n  vary:\n    initial.psi_dot: {values: [0, 1, 2, 3, 4, 6, 8, 10]}\n' \
        "$src/models/heavy_top.yaml" "$1"
}
# the largest relative difference of the columns PREFIX* of two summary.csv files
largest() { # prefix a b
    awk -F, -v prefix="$1" 'NR == FNR { if (FNR > 1) for (i = 1; i <= NF; ++i) a[FNR, i] = $i; else h = $0; next }
        FNR == 1 { n = split($0, head, ","); next }
        { for (i = 1; i <= n; ++i) if (index(head[i], prefix) == 1 && $i != "" && $i != a[FNR, i]) {
              x = a[FNR, i] + 0; d = $i - x; if (x != 0) d /= x; if (d < 0) d = -d; if (d > w) w = d } }
        END { printf "%.1e", w + 0 }' "$2" "$3"
}
digits() { awk -v d="$1" 'BEGIN { if (d == 0) print "all"; else printf "%d", -log(d) / log(10) }'; }
echo "# Lanes against the runs without them"
echo
echo "Written by \`bash bench/lanes/agreement.sh build/rotgen > bench/results/lanes_agreement.md\`."
echo
echo "| sweep | integrator | lanes | final.* largest relative difference | digits | event.* largest relative difference |"
echo "|---|---|---|---|---|---|"
row() { # name, scene function, integrator, lanes
    local d="$work/$1_$RANDOM" f e
    "$2" "$3" >"$d.yaml"
    "$rotgen" sweep "$d.yaml" -o "${d}_scalar" -j 2 -q
    "$rotgen" sweep "$d.yaml" -o "${d}_lanes" -j 2 --lanes "$4" -q
    f=$(largest final. "${d}_scalar/summary.csv" "${d}_lanes/summary.csv")
    e=$(largest event. "${d}_scalar/summary.csv" "${d}_lanes/summary.csv")
    echo "| $1 | \`$3\` | $4 | $f | $(digits "$f") | $( [ "$2" = falling ] && echo "$e" || echo "-") |"
}
row heavy_tops top "{method: rk4, step: 0.01}" 4
row heavy_tops top "{method: dop853, rtol: 1e-8, atol: 1e-10}" 4
row falling_tops falling "{method: rk4, step: 0.01}" 8
row falling_tops falling "{method: dop853, rtol: 1e-12, atol: 1e-12}" 8
