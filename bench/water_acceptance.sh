#!/bin/sh
# Water's acceptance runs (bench/VALIDATION.md, "Still water"): the tank at rest (bench/still_water)
# in 2D, two tank shapes (1 m and 0.5 m wide, 0.5 m deep), depth/dp 25 over 60 s, 50 over 20 s
# and 100 over 10 s (0.5 m wide), with analytic walls and with a wall body; in 3D at depth/dp 20
# over 6 s; and the first standing wave (examples/standing_wave) at kh 0.5, 1, 2, 3 and depth/dp
# 25 and 50 (5 periods) and 100 (kh 1, 2, 3; 1.6 periods: four zero crossings), inviscid, and one
# viscous wave against Lamb. All at c0 = 10 sqrt(g H) and h = 2 dp, one thread a run, JOBS runs
# at a time.
#   sh bench/water_acceptance.sh               about 50 min on 2 cores (the EPYC)
#   QUICK=1 sh bench/water_acceptance.sh       depth/dp 25 only: about 3 min
# Writes one log a run to bench/results/$MACHINE/water/ and their RESULT lines to water.md there
# (the waves' CSV and VTK to build/water/).
set -eu
cd "$(dirname "$0")/.."
MACHINE=${MACHINE:-c-2core-epyc}
JOBS=${JOBS:-2}
OUT=bench/results/$MACHINE/water
mkdir -p "$OUT"
make -s build/still_water build/standing_wave
LIST=$OUT/jobs.txt
: > "$LIST"
still() { echo "still_$1|./build/still_water $2" >> "$LIST"; }
wave() { echo "wave_$1|./build/standing_wave --quiet --out build/water/$1 $2" >> "$LIST"; }
if [ "${QUICK:-0}" = 1 ]; then
    still "2d_w1_r25" "--res 25 --width 1 --tend 20"
    still "2d_w05_r25" "--res 25 --width 0.5 --tend 20"
    still "2d_w1_r25_body" "--res 25 --width 1 --walls body --tend 10"
    for kh in 0.5 1 2 3; do wave "kh${kh}_r25" "--kh $kh --res 25 --periods 5"; done
else
    wave "kh0.5_r50" "--kh 0.5 --res 50 --periods 5"
    still "2d_w05_r100" "--res 100 --width 0.5 --tend 10"
    still "3d_r20" "--dim 3 --res 20 --width 1 --breadth 0.25 --tend 6"
    wave "kh1_r100" "--kh 1 --res 100 --periods 1.6"
    still "2d_w1_r50" "--res 50 --width 1 --tend 20"
    still "2d_w1_r25_body" "--res 25 --width 1 --walls body --tend 60"
    still "2d_w1_r25" "--res 25 --width 1 --tend 60"
    wave "kh1_r50" "--kh 1 --res 50 --periods 5"
    wave "kh1_r50_mu5" "--kh 1 --res 50 --periods 5 --viscosity 5"
    wave "kh2_r100" "--kh 2 --res 100 --periods 1.6"
    still "2d_w05_r50" "--res 50 --width 0.5 --tend 20"
    wave "kh3_r100" "--kh 3 --res 100 --periods 1.6"
    still "2d_w05_r25" "--res 25 --width 0.5 --tend 60"
    for kh in 2 3; do wave "kh${kh}_r50" "--kh $kh --res 50 --periods 5"; done
    for kh in 0.5 1 2 3; do wave "kh${kh}_r25" "--kh $kh --res 25 --periods 5"; done
fi
# (the list starts with the longest runs, so that the lanes end together)
tr '\n' '\0' < "$LIST" | xargs -0 -P "$JOBS" -I{} sh -c 'name=${1%%|*}; cmd=${1#*|}; $cmd > "$2/$name.log" 2>&1 || echo "FAILED $name" >> "$2/$name.log"' _ {} "$OUT"
{
    echo "# Water acceptance runs ($MACHINE, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'))"
    echo
    for f in "$OUT"/*.log; do echo "- $(basename "$f" .log): $(grep -h '^RESULT\|^FAILED' "$f" | tr '\n' ' ')"; done
} > "$OUT/water.md"
cat "$OUT/water.md"
