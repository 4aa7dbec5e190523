#!/bin/sh
# user_scenes_map.sh - the stability map's rows for the scenes users write: every shear
# formulation x rotation on bench/user_scenes.c's scenes (short runs, one thread):
#   drop     2D disc / 3D cube dropped on a no-slip and a free-slip floor, spin 0, 20, 50 rad/s
#   ramp     rolling (2D) or tumbling (3D) down a 30-degree no-slip ramp
#   collide  two spinning bodies thrown at each other
#   stack, slide, tank   blocks filled flush on a floor and on each other; a block thrown along a
#            floor with friction; water with jelly rafts filled flush on it
#   gravity-z, friction-deg, slot   the quiet mistakes (warned; the default body)
# Classes: stable (the watchdog's growth below 2 % of the largest mechanical energy, to the end),
# unstable (stopped with a clean SPS_ERR_UNSTABLE message), refused (a set-up check at the first
# step), rejected (a refused combination, e.g. OAS in 3D), GAINED (ran to the end with growth >= 2 %: counted in sps_diagnostics, not silent,
# but not stable either), CRASH (anything else: must never happen).
# With a third argument "rigid": the free rigid bodies' rows instead (drop, ramp, collide, drop-stack,
# float; the 3D float at dp 0.02), written to user_scenes_map_rigid_<dims>d.csv.
# Usage: sh bench/user_scenes_map.sh [dims] [t_end] [rigid]    (default "2 3" 0.3; writes
# bench/results/<machine>/user_scenes_map_<dims>d.csv, machine = $MACHINE or c-2core-xeon)
set -eu
cd "$(dirname "$0")/.."
dims=${1:-"2 3"}
t_end=${2:-0.3}
kind=${3:-elastic}
out=bench/results/${MACHINE:-c-2core-xeon}/user_scenes_map_$([ "$kind" = rigid ] && echo rigid_)$(echo "$dims" | tr -d " ")d.csv
mkdir -p "$(dirname "$out")"
make -s build/user_scenes
echo "dim,scene,slip,spin,shear,rotation,class,watchdog_growth,events,message" > "$out"
run() { # dim scene slip spin shear rotation [more options]
    set +e
    line=$(timeout 600 nice -n 10 ./build/user_scenes --dim "$1" --scene "$2" --slip "$3" --spin "$4" --shear "$5" --rotation "$6" \
        --tend "$t_end" --kind "$kind" ${7:-} 2> /tmp/user_scenes_map.$$)
    status=$?
    set -e
    growth=$(printf '%s\n' "$line" | tr ' ' '\n' | sed -n 's/^watchdog_growth=//p')
    events=$(printf '%s\n' "$line" | tr ' ' '\n' | sed -n 's/^watchdog_events=//p')
    message=$(head -n 1 /tmp/user_scenes_map.$$ | tr ',' ';' | cut -c1-160)
    if [ "$status" -eq 0 ] && [ -n "$growth" ]; then
        if [ "$(echo "$growth < 0.02" | bc)" -eq 1 ]; then class=stable; else class=GAINED; fi
    elif [ "$status" -eq 2 ] && printf '%s' "$line" | grep -q 'status=unstable'; then class=unstable
    elif [ "$status" -eq 2 ] && printf '%s' "$line" | grep -q 'status=refused'; then class=refused
    elif [ "$status" -eq 2 ] && [ -z "$line" ]; then class=rejected
    else class=CRASH; fi
    echo "$1,$2,$3,$4,$5,$6,$class,$growth,$events,$message" >> "$out"
}
for dim in $dims; do
    if [ "$kind" = rigid ]; then
        for spin in 0 20 50; do
            for slip in noslip free; do run "$dim" drop "$slip" "$spin" default default; done
        done
        run "$dim" ramp noslip 0 default default
        run "$dim" collide noslip 20 default default
        run "$dim" drop-stack noslip 0 default default
        run "$dim" drop-stack free 0 default default
        run "$dim" float free 0 default default "$([ "$dim" = 3 ] && echo "--dp 0.02")"
        continue
    fi
    for shear in eno eno-a og oas gno gno-a; do
        case $shear in eno-a|gno-a) rotations="mean particle pair" ;; *) rotations="pair" ;; esac
        for rotation in $rotations; do
            for spin in 0 20 50; do
                for slip in noslip free; do run "$dim" drop "$slip" "$spin" "$shear" "$rotation"; done
            done
            run "$dim" ramp noslip 0 "$shear" "$rotation"
            run "$dim" collide noslip 20 "$shear" "$rotation"
            for scene in stack slide tank; do run "$dim" "$scene" free 0 "$shear" "$rotation"; done
        done
    done
    for scene in friction-deg slot; do run "$dim" "$scene" free 0 default default; done
done
run 2 gravity-z free 0 default default
rm -f /tmp/user_scenes_map.$$
echo "$out:"; cut -d, -f7 "$out" | tail -n +2 | sort | uniq -c
