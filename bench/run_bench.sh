#!/bin/sh
# Speed of the plate benchmarks: wall time and ns per particle per acoustic step, for
# 1 and 2 threads and dual vs single stepping. Writes bench/results/$MACHINE/plates.csv.
#   sh bench/run_bench.sh            full table (about 40 min on 2 idle cores)
#   QUICK=1 sh bench/run_bench.sh    H/dp = 10 and 3D H/dp = 3 only (about 8 min)
#   RES2="20 30" RES3="5" APPEND=1 sh bench/run_bench.sh   add resolutions to the table
#   GEOS=frozen APPEND=1 sh bench/run_bench.sh              add one pair geometry's rows
# Run on an otherwise idle machine: the numbers are wall-clock times (minimum of REPEAT runs).
set -eu
cd "$(dirname "$0")/.."
MACHINE=${MACHINE:-c-2core-xeon} # the results folder of the machine the README reports; set MACHINE on another
REPEAT=${REPEAT:-1}
OUT=bench/results/$MACHINE
mkdir -p "$OUT"
CSV=$OUT/plates.csv
make -s examples
# APPEND=1 adds rows to an existing table (e.g. RES2="20 30" RES3="5" APPEND=1 after a QUICK run)
if [ "${APPEND:-0}" != 1 ] || [ ! -f "$CSV" ]; then
    echo "scene,res,particles,threads,stepping,geometry,t_end,acoustic_steps,advection_steps,wall_s,ns_per_particle_step" > "$CSV"
fi

# field KEY LINE: the value of key=value in a RESULT line
field() { echo "$2" | tr ' ' '\n' | sed -n "s/^$1=//p"; }

run() { # scene res t_end threads stepping extra-args...
    scene=$1 res=$2 tend=$3 thr=$4 st=$5; shift 5
    best=""
    r=1
    while [ "$r" -le "$REPEAT" ]; do
        line=$(./build/"$scene" --quiet --res "$res" --tend "$tend" --threads "$thr" --stepping "$st" \
               --vtk-every 0 --csv-every 1 --out "out/bench_$scene" "$@" | grep '^RESULT')
        wall=$(field wall_s "$line")
        if [ -z "$best" ] || awk "BEGIN{exit !($wall < $best)}"; then best=$wall; bestline=$line; fi
        r=$((r + 1))
    done
    n=$(field particles "$bestline"); steps=$(field steps "$bestline"); adv=$(field advection_steps "$bestline")
    ns=$(awk "BEGIN{printf \"%.1f\", 1e9 * $best / ($n * $steps)}")
    echo "$scene,$res,$n,$thr,$st,$geo,$tend,$steps,$adv,$best,$ns" | tee -a "$CSV"
}

if [ "${QUICK:-0}" = 1 ]; then RES2=${RES2-10}; RES3=${RES3-3}; else RES2=${RES2-"10 20 30"}; RES3=${RES3-"3 5"}; fi
# Horizons: t = 1 s at H/dp = 10 (the paper's Table 2 horizon, and the speed target); shorter at
# finer resolution, where ns per particle-step is the figure (wall time scales with t_end).
for geo in ${GEOS-recomputed frozen}; do
    for res in $RES2; do
        case $res in 10) tend=1 ;; 20) tend=0.05 ;; *) tend=0.02 ;; esac
        for thr in 1 2; do for st in dual single; do run plate2d "$res" "$tend" "$thr" "$st" --shear eno-a --geometry "$geo"; done; done
    done
    for res in $RES3; do
        case $res in 3) tend=0.002 ;; *) tend=0.0005 ;; esac
        for thr in 1 2; do for st in dual single; do run plate3d "$res" "$tend" "$thr" "$st" --shear eno-a --mode 2,2 --full --geometry "$geo"; done; done
    done
done
echo "written $CSV"
