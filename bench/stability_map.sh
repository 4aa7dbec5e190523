#!/bin/sh
# stability_map.sh - where each shear formulation stays stable, one knob at a time.
#
# Runs the 2D plate (examples/plate2d, H/dp = 5, to t = 0.3 s) and the spinning plate
# (examples/spinning_plate, dp = 0.1, to t = 0.2 s) for each shear formulation, varying one knob
# from the default while the others keep theirs:
#   nu      0.3 0.45 0.49 0.499        (default: the case's own, 0.3975 / 0.45)
#   v_f     0.05 0.1 0.2               (plate; default 0.05)
#   omega   50 100 200 rad/s           (spinning plate; default 50)
#   jitter  0 0.1 0.3 dp               (each coordinate moved by U(-j/2, j/2) dp, seed 1; default 0)
#   cfl     0.4 0.8 1.0 1.5            (acoustic CFL; default 0.4; 1.5 is outside the allowed (0, 1])
# and the 3D plate (examples/plate3d, H/dp = 3, mode (2,2), to t = 0.002 s; 43,200 particles) at
#   cfl     0.4 0.5 0.6 0.8 1.0
# Each run is classified:
#   stable     ran to the end, hourglass indicator max < 0.02 and min spacing > 0.5 dp
#   degraded   ran to the end, but the hourglass indicator reached 0.02 (zigzag) or particles
#              came closer than 0.5 dp (clustering)
#   +energy    added to either when the energy watchdog warned (the energy grew by more than
#              5 % of its largest mechanical energy): a blow-up is never silent
#   unstable   stopped with a clean SPS_ERR_UNSTABLE message (exit status 2)
#   rejected   refused with a validation message naming option, value and range (exit status 2)
#   CRASH      any other exit, or still running after the timeout: must never happen
# Writes bench/results/<machine>/stability_map.csv and prints a markdown table.
# One thread per run at nice 10 (the other core stays free for timing work).
# Usage: sh bench/stability_map.sh [machine-name]     (default c-2core-xeon; ~10 min, the 3D rows ~15 min more)
set -eu
cd "$(dirname "$0")/.."
machine=${1:-c-2core-xeon}
out_dir=bench/results/$machine
csv=$out_dir/stability_map.csv
tmp=${TMPDIR:-/tmp}/sphsolid_stability_$$
timeout_s=300
hourglass_limit=0.02
spacing_limit=0.5
mkdir -p "$out_dir" "$tmp"
trap 'rm -rf "$tmp"' EXIT
make -s examples

shears="og oas eno eno-a gno gno-a"
echo "case,knob,value,shear,class,exit,hourglass_max,min_spacing,wall_s,message" > "$csv"

# field NAME LINE: the value of NAME=... in a RESULT line
field() { printf '%s\n' "$2" | tr ' ' '\n' | sed -n "s/^$1=//p" | head -n 1; }

# run CASE KNOB VALUE SHEAR ARGS...: one run, one CSV row
run() {
    case_name=$1 knob=$2 value=$3 shear=$4
    shift 4
    set +e
    start=$(date +%s.%N)
    timeout "$timeout_s" nice -n 10 "./build/$case_name" --shear "$shear" --threads 1 --quiet --vtk-every 0 \
        --out "$tmp/run" "$@" > "$tmp/stdout" 2> "$tmp/stderr"
    status=$?
    end=$(date +%s.%N)
    set -e
    wall=$(echo "$end - $start" | bc)
    result=$(grep '^RESULT' "$tmp/stdout" || true)
    message=$(head -n 1 "$tmp/stderr" | sed 's/^[^:]*: //' | tr ',' ';' | cut -c1-240)
    hg=""; ms=""
    if [ "$status" -eq 0 ] && [ -n "$result" ]; then
        hg=$(field hourglass_max "$result"); ms=$(field min_spacing "$result")
        if [ "$(echo "$hg < $hourglass_limit && $ms > $spacing_limit" | bc)" -eq 1 ]; then class=stable; else class=degraded; fi
        message=""
        if grep -q 'energy watchdog' "$tmp/stderr"; then class="$class+energy"; message=$(grep -m 1 'energy watchdog' "$tmp/stderr" | cut -c1-200 | tr ',' ';'); fi
    elif [ "$status" -eq 2 ] && grep -q 'simulation unstable' "$tmp/stderr"; then
        class=unstable
    elif [ "$status" -eq 2 ] && grep -q 'outside \[' "$tmp/stderr"; then
        class=rejected
    else
        class=CRASH
        [ "$status" -eq 124 ] && message="timeout after $timeout_s s"
    fi
    echo "$case_name,$knob,$value,$shear,$class,$status,$hg,$ms,$wall,$message" >> "$csv"
}

total_start=$(date +%s)
for shear in $shears; do
    for v in 0.3 0.45 0.49 0.499; do run plate2d nu "$v" "$shear" --res 5 --tend 0.3 --nu "$v"; done
    for v in 0.05 0.1 0.2; do run plate2d vf "$v" "$shear" --res 5 --tend 0.3 --vf "$v"; done
    for v in 0 0.1 0.3; do run plate2d jitter "$v" "$shear" --res 5 --tend 0.3 --jitter "$v"; done
    for v in 0.4 0.8 1.0 1.5; do run plate2d cfl "$v" "$shear" --res 5 --tend 0.3 --cfl "$v"; done
    for v in 0.3 0.45 0.49 0.499; do run spinning_plate nu "$v" "$shear" --dp 0.1 --tend 0.2 --nu "$v"; done
    for v in 50 100 200; do run spinning_plate omega "$v" "$shear" --dp 0.1 --tend 0.2 --omega "$v"; done
    for v in 0 0.1 0.3; do run spinning_plate jitter "$v" "$shear" --dp 0.1 --tend 0.2 --jitter "$v"; done
    for v in 0.4 0.8 1.0 1.5; do run spinning_plate cfl "$v" "$shear" --dp 0.1 --tend 0.2 --cfl "$v"; done
done
for shear in $shears; do
    [ "$shear" = oas ] && continue # 2D only
    for v in 0.4 0.5 0.6 0.8 1.0; do run plate3d cfl "$v" "$shear" --res 3 --mode 2,2 --full --tend 0.002 --cfl "$v"; done
done
total=$(( $(date +%s) - total_start ))

# markdown: one row per case and knob value, one column per shear formulation
printf '| case | knob | value |'; for s in $shears; do printf ' %s |' "$s"; done; printf '\n'
printf '|---|---|---|'; for s in $shears; do printf -- '---|'; done; printf '\n'
tail -n +2 "$csv" | cut -d, -f1-3 | awk '!seen[$0]++' | while IFS=, read -r c k v; do
    printf '| %s | %s | %s |' "$c" "$k" "$v"
    for s in $shears; do
        printf ' %s |' "$(awk -F, -v c="$c" -v k="$k" -v v="$v" -v s="$s" '$1 == c && $2 == k && $3 == v && $4 == s { print $5 }' "$csv")"
    done
    printf '\n'
done
runs=$(tail -n +2 "$csv" | wc -l)
crashes=$(grep -c ',CRASH,' "$csv" || true)
echo
echo "$runs runs in $total s, $crashes crashes or hangs; CSV: $csv"
[ "$crashes" -eq 0 ]
