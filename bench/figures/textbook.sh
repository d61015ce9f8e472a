#!/usr/bin/env bash
# The README's textbook figures (chapter section 5.6), from `rotgen simulate`'s figure data:
#
#   bash bench/figures/textbook.sh build/rotgen
#
# docs/heavy_top_regimes.png: the heavy top's figure axis in its three regimes (5.6.1), the shipped
#   scenes heavy_top_{cusps,loops,waves}.yaml run with --plot-axis, side by side;
# docs/polhodes.png: polhodes of the free asymmetric top I = (1, 2, 3) (5.6.3; `rotgen simulate
#   --plot-polhode`), L / |L| on one unit sphere: closed curves about the axes of least and
#   greatest moment (blue), and the two started next to the middle axis (red), which leave it.
set -euo pipefail
rotgen=$(realpath "${1:?usage: textbook.sh ROTGEN}")
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
for r in cusps loops waves; do
  "$rotgen" simulate "$root/models/scenes/heavy_top_$r.yaml" -o "$r.csv" --plot-axis "$r.png" -q
done
# free asymmetric top, |L| = 1 at the start: L in the plane of axes 1 and 3 at angles from axis 1,
# and two starts a little off axis 2 (the separatrices' neighbours)
polhode() { # $1: name, $2 $3 $4: L at the start (omega = L / I, I = 1, 2, 3)
  cat >"$1.yaml" <<YAML
model: $root/models/free_asymmetric_top.yaml
form: body
initial: {phi: 0, theta: 0.3, psi: 0, omega1: $2, omega2: $(echo "$3 / 2" | bc -l), omega3: $(echo "$4 / 3" | bc -l)}
time: {start: 0, end: 40, samples: 4001}
integrator: {method: dop853, rtol: 1e-10, atol: 1e-12}
record: [omega1]
YAML
  "$rotgen" simulate "$1.yaml" -o "$1.csv" --plot-polhode "$1.png" -q
}
i=0
for deg in 15 35 55 75; do # cos, sin of the angle from axis 1, in the 1-3 plane
  c=$(echo "c($deg * 4 * a(1) / 180)" | bc -l) s=$(echo "s($deg * 4 * a(1) / 180)" | bc -l)
  polhode "p$((i++))" "$c" 0 "$s"
done
polhode p4 0.05 0.998749 0
polhode p5 0 0.998749 0.05

gnuplot <<'GP'
set terminal pngcairo size 1200,760 noenhanced
set output 'heavy_top_regimes.png'
set datafile separator ','
set grid
set key off
set multiplot layout 2,3 title 'the heavy top (heavy_top.yaml) tilted 0.5 rad, psi_dot = 5: its figure axis on the unit sphere'
set parametric
set trange [0:2*pi]
set size ratio -1
set xrange [-0.85:0.85]
set yrange [-0.85:0.85]
do for [r in "cusps loops waves"] {
  label = r.': phi_dot(0) = '.(r eq 'cusps' ? '0' : r eq 'loops' ? '-0.2' : '0.15').', seen from above'
  set title label
  plot cos(t), sin(t) lc rgb 'gray', r.'.axis.csv' using 2:3 every ::1 with lines lw 1.5
}
unset parametric
set size noratio
set xrange [*:*]
set yrange [*:*] reverse
set xlabel 'azimuth (rad)'
do for [r in "cusps loops waves"] {
  set title 'polar angle against azimuth'
  label = (r eq 'cusps' ? 'polar angle (rad)' : '')
  set ylabel label
  plot r.'.axis.csv' using 6:5 every ::1 with lines lw 1.5
}
unset multiplot

reset
set terminal pngcairo size 800,720 noenhanced
set output 'polhodes.png'
set datafile separator ','
set view equal xyz
set view 62, 28
set xyplane 0
set parametric
set isosamples 25, 13
set urange [0:2*pi]
set vrange [-pi/2:pi/2]
set hidden3d front
set key off
set title 'free asymmetric top, I = (1, 2, 3): polhodes, L / |L| in the body frame'
set xlabel 'L1'
set ylabel 'L2'
set zlabel 'L3'
n(a,b,c) = sqrt(a*a + b*b + c*c)
splot cos(u)*cos(v), sin(u)*cos(v), sin(v) with lines lc rgb '#d0d0d0', \
  for [i=0:5] 'p'.i.'.polhode.csv' using ($5/n($5,$6,$7)):($6/n($5,$6,$7)):($7/n($5,$6,$7)) \
  every ::1 with lines lw 2.5 lc rgb (i < 4 ? '#1060c0' : '#c01010')
GP
cp heavy_top_regimes.png polhodes.png "$root/docs/"
echo "wrote docs/heavy_top_regimes.png and docs/polhodes.png"
