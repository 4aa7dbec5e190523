#!/bin/sh
# Stability map of the contact cases: the colliding rings (A5) at dp 0.002 and the ball hitting
# a plate (A9) at dp 0.005, for each shear formulation and impact speed up to 0.2 c0. Each cell: stable (hourglass indicator below 0.01
# and smallest spacing above 0.7 dp over the run), degraded (it runs to the end but zigzags or
# clusters), or error (the library stopped it with a message). Writes a markdown table to stdout.
# Usage: sh bench/contact_map.sh > bench/results/<machine>/contact_map.md   (about 8 minutes)
set -u
BIN=${BIN:-./build/rings2d}
BALL=${BALL:-./build/ball_plate2d}
OUT=${OUT:-/tmp/contact_map}
echo "| rings2d, dp 0.002 | 0.06 c0 | 0.10 c0 | 0.15 c0 | 0.20 c0 |"
echo "|---|---|---|---|---|"
for shear in og oas eno eno-a gno gno-a; do
  row="| $shear |"
  for v in 0.06 0.10 0.15 0.20; do
    line=$($BIN --dp 0.002 --v0 $v --shear $shear --tend 0.012 --vtk-every 0 --png-every 0 --quiet --out $OUT/$shear-$v 2>&1 | tail -n 1)
    case "$line" in
      RESULT*)
        hg=$(echo "$line" | sed 's/.*hourglass_max=\([^ ]*\).*/\1/')
        sp=$(echo "$line" | sed 's/.*min_spacing=\([^ ]*\).*/\1/')
        rise=$(echo "$line" | sed 's/.*energy_rise_max=\([^ ]*\).*/\1/')
        verdict=$(awk -v h="$hg" -v s="$sp" 'BEGIN { print (h < 0.01 && s > 0.7) ? "stable" : "degraded" }')
        row="$row $verdict (hourglass $hg, spacing $sp, energy rise $rise) |";;
      *) row="$row error: $(echo "$line" | cut -c1-80) |";;
    esac
  done
  echo "$row"
done
echo
echo "| ball_plate2d, dp 0.005 | 0.02 c0 | 0.06 c0 | 0.12 c0 | 0.20 c0 |"
echo "|---|---|---|---|---|"
for shear in og oas eno eno-a gno gno-a; do
  row="| $shear |"
  for v in 0.02 0.06 0.12 0.20; do
    line=$($BALL --dp 0.005 --v0 $v --shear $shear --tend 0.015 --vtk-every 0 --png-every 0 --quiet --out $OUT/ball-$shear-$v 2>&1 | tail -n 1)
    case "$line" in
      RESULT*)
        hg=$(echo "$line" | sed 's/.*hourglass_max=\([^ ]*\).*/\1/')
        sp=$(echo "$line" | sed 's/.* min_spacing=\([^ ]*\).*/\1/')
        ke=$(echo "$line" | sed 's/.*kinetic_max_rel=\([^ ]*\).*/\1/')
        verdict=$(awk -v h="$hg" -v s="$sp" 'BEGIN { print (h < 0.01 && s > 0.7) ? "stable" : "degraded" }')
        row="$row $verdict (hourglass $hg, spacing $sp, kinetic max/start $ke) |";;
      *) row="$row error: $(echo "$line" | cut -c1-80) |";;
    esac
  done
  echo "$row"
done
