#!/bin/sh
# The most that fusing the GNO penalty pass into another neighbour pass can buy
# (bench/VALIDATION.md, "Pass fusion"): the examples built as they are and built with the
# penalty pass skipped (a copy of the header with its call in sps__acoustic_substep disabled:
# no fused loop can cost less than no loop at all), run interleaved by bench/instancing_cost.sh.
# The GNO-A plate's ratio ablated / as-is bounds the fused plate's; the ENO-A plate and the OG
# column collapse run no penalty pass, so theirs should be 1 and show the machine's noise.
#   sh bench/pass_fusion.sh [ROUNDS]
# Defaults: 3 rounds, --threads 1 and 2 (THREADS), the plate to t = 0.3 and the column collapse to
# t = 0.1 (TEND_PLATE2D, TEND_COLUMN). Medians mean something on a quiet
# machine only (see bench/instancing_cost.sh).
#
# The penalty in the pressure pass (penalty_in_pressure_pass, the examples' --penalty fused)
# against the paper's pass of its own, both from the same binaries, interleaved (paper, fused,
# fused, paper, ...), one thread, user CPU seconds; medians and paper / fused (the speed-up):
#   sh bench/pass_fusion.sh fused [ROUNDS]
# Cases: plate2d --res 10 --shear gno-a --tend 0.3; plate3d --res 3 --shear gno-a to
# TEND_PLATE3D (default 0.002 s); the 3D jelly build/float/realtime --dim 3 --dp 0.0765 --E 1e5
# --omega 2 --frames 200 --tend 100 --budget 0 (also its physics_ms_mean). Each RESULT line's
# figures are printed, so both forms' answers can be compared.
set -eu
cd "$(dirname "$0")/.."
if [ "${1:-}" = fused ]; then
    rounds=${2:-3}
    tend_plate3d=${TEND_PLATE3D:-0.002}
    make -s build/plate2d build/plate3d build/float/realtime
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    cases="plate2d|build/plate2d --res 10 --shear gno-a --tend 0.3
plate3d|build/plate3d --res 3 --shear gno-a --tend $tend_plate3d
jelly3d|build/float/realtime --dim 3 --dp 0.0765 --E 1e5 --omega 2 --frames 200 --tend 100 --budget 0"
    run() { # case name, penalty, command line -> "name penalty user_s physics_ms" into $tmp/times
        # shellcheck disable=SC2086
        /usr/bin/time -f "%U" -o "$tmp/cpu" $3 --threads 1 --penalty "$2" --quiet --vtk-every 0 --out "$tmp/o" > "$tmp/log" 2>&1
        grep '^RESULT' "$tmp/log" | sed "s/^/$1 $2: /"
        echo "$1 $2 $(cat "$tmp/cpu") $(sed -n 's/.*physics_ms_mean=\([0-9.]*\).*/\1/p' "$tmp/log" | head -1)" >> "$tmp/times"
        tail -n 1 "$tmp/times" | sed 's/^/times: /'
    }
    r=1
    while [ "$r" -le "$rounds" ]; do
        echo "$cases" | while IFS='|' read -r name cmd; do
            if [ $((r % 2)) -eq 1 ]; then run "$name" paper "$cmd"; run "$name" fused "$cmd"
            else run "$name" fused "$cmd"; run "$name" paper "$cmd"; fi
        done
        r=$((r + 1))
    done
    echo "case paper_user_s fused_user_s paper/fused [paper_physics_ms fused_physics_ms] (medians of $rounds interleaved rounds, 1 thread)"
    awk -f bench/medians.awk "$tmp/times" | awk '
        $2 == "paper" { pu[$1] = $3; pm[$1] = $4 }
        $2 == "fused" { fu[$1] = $3; fm[$1] = $4 }
        END {
            for (c in pu) {
                line = sprintf("%s %.2f %.2f %.3f", c, pu[c], fu[c], pu[c] / fu[c])
                if (pm[c] != "") line = line sprintf(" %.2f %.2f", pm[c], fm[c])
                print line
            }
        }' | sort
    exit 0
fi
rounds=${1:-3}
bins="build/plate2d build/plate3d build/column_collapse2d"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# shellcheck disable=SC2086
make -s $bins
mkdir "$tmp/ablated"
cp -r sphsolid.h Makefile examples "$tmp/ablated/"
call='if (w->bodies\[bi\]\.model\.pass\.penalty) sps__run_groups'
if [ "$(grep -c "$call" sphsolid.h)" -ne 1 ]; then
    echo "pass_fusion.sh: the penalty pass's call in sps__acoustic_substep was not found once; update the pattern" >&2
    exit 1
fi
sed "s/$call/if (0 \&\& w->bodies[bi].model.pass.penalty) sps__run_groups/" sphsolid.h > "$tmp/ablated/sphsolid.h"
# shellcheck disable=SC2086
(cd "$tmp/ablated" && make -s $bins)
echo "old = as built, new = without the penalty pass"
TEND_PLATE2D=${TEND_PLATE2D:-0.3} TEND_COLUMN=${TEND_COLUMN:-0.1} sh bench/instancing_cost.sh build "$tmp/ablated/build" "$rounds"
