#!/bin/sh
# Draws docs/gyrostat_tilt.png: the angle of body axis 2 from its start (space z) against t for
# the gyrostat satellite spun about its intermediate axis, with the wheel almost at rest
# (models/scenes/gyrostat_tumbling.yaml) and spun up beyond the threshold that
# `rotgen inspect --inertia` reports (models/scenes/gyrostat_steady.yaml).
#   sh docs/gyrostat_tilt.sh build/rotgen
set -eu
rotgen=$1
root=$(dirname "$0")/..
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$rotgen" simulate "$root/models/scenes/gyrostat_tumbling.yaml" -o "$work/tumbling.csv"
"$rotgen" simulate "$root/models/scenes/gyrostat_steady.yaml" -o "$work/steady.csv"
gnuplot <<PLOT
set terminal pngcairo size 800,400 noenhanced
set output "$root/docs/gyrostat_tilt.png"
set datafile separator ","
set key autotitle columnhead
set xlabel "t"
set ylabel "tilt of body axis 2 (degrees)"
set key top left
col(n) = column(n)
plot "< grep -v '^#' $work/tumbling.csv" using 1:(acos(column("body_y_z"))*180/pi) with lines title "p_wheel = 0.1 (h/omega inside the unstable band)", \\
     "< grep -v '^#' $work/steady.csv" using 1:(acos(column("body_y_z"))*180/pi) with lines title "p_wheel = 1.5 (beyond the threshold h/omega = 1)"
PLOT
