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
# map TITLE PROGRAM DP TEND KEY LABEL PREFIX SPEEDS...: one table, a row per shear formulation and
# a cell per impact speed (in c0), each run's verdict with its hourglass and spacing maxima and
# the RESULT value KEY (shown as LABEL)
map() {
  title=$1 program=$2 dp=$3 tend=$4 key=$5 label=$6 prefix=$7
  shift 7
  printf '| %s |' "$title"; for v in "$@"; do printf ' %s c0 |' "$v"; done; printf '\n'
  printf '|---|'; for v in "$@"; do printf -- '---|'; done; printf '\n'
  for shear in og oas eno eno-a gno gno-a; do
    row="| $shear |"
    for v in "$@"; do
      line=$($program --dp $dp --v0 $v --shear $shear --tend $tend --vtk-every 0 --png-every 0 --quiet --out $OUT/$prefix$shear-$v 2>&1 | tail -n 1)
      case "$line" in
        RESULT*)
          hg=$(echo "$line" | sed 's/.*hourglass_max=\([^ ]*\).*/\1/')
          sp=$(echo "$line" | sed 's/.* min_spacing=\([^ ]*\).*/\1/')
          value=$(echo "$line" | sed "s/.*$key=\([^ ]*\).*/\1/")
          verdict=$(awk -v h="$hg" -v s="$sp" 'BEGIN { print (h < 0.01 && s > 0.7) ? "stable" : "degraded" }')
          row="$row $verdict (hourglass $hg, spacing $sp, $label $value) |";;
        *) row="$row error: $(echo "$line" | cut -c1-80) |";;
      esac
    done
    echo "$row"
  done
}
map "rings2d, dp 0.002" "$BIN" 0.002 0.012 energy_rise_max "energy rise" "" 0.06 0.10 0.15 0.20
echo
map "ball_plate2d, dp 0.005" "$BALL" 0.005 0.015 kinetic_max_rel "kinetic max/start" ball- 0.02 0.06 0.12 0.20
