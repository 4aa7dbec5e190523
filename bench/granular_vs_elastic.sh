#!/bin/sh
# The granular pass's cost against the elastic plate's, per particle and acoustic sub-step
# (bench/VALIDATION.md, "Granular pass cost"): the column collapse (C4, 5000 soil particles,
# Drucker-Prager, OG with the stress diffusion and the limited Riemann dissipation) against the
# 2D plate (A1, H/dp 10, ENO-A elastic), run interleaved, ROUNDS rounds, medians, and the ratio
# granular / elastic; with two build dirs (old, new: any two builds of the two examples) also
# new / old per case.
#   bench/granular_vs_elastic.sh BUILD_DIR [NEW_BUILD_DIR] [ROUNDS]
# e.g. make build/column_collapse2d build/plate2d, then bench/granular_vs_elastic.sh build "" 3
# What is counted: the library's sub-steps only (the examples' CSV rows, VTK files and pictures
# switched off: --csv-every beyond the run, --vtk-every 0, --png-every 0), the particles each
# example reports: the soil's 5000 for the column (its tank walls are analytic, their mirror
# images no particles) and all 1040 of the plate (its 40 clamp particles run every pass). One
# thread: CPU time (user + system from /usr/bin/time; a run waiting for a core does not count),
# setup included (under 2 % of either run); two threads (THREADS="1 2"): the wall time the
# examples print, which means something only on a quiet machine.
set -eu
old=${1:?build dir}
new=${2:-}
rounds=${3:-3}
threads_list=${THREADS:-1}
tend_column=${TEND_COLUMN:-0.1}
tend_plate=${TEND_PLATE:-0.3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
quiet_output="--quiet --vtk-every 0 --png-every 0 --csv-every 1000"
cases="granular|column_collapse2d --tend $tend_column
elastic|plate2d --res 10 --tend $tend_plate --shear eno-a"
run() { # build dir, build label, threads, case name, command line -> "case build threads ns_wall ns_cpu" into $out/times
    # shellcheck disable=SC2086
    /usr/bin/time -f "%U %S" -o "$out/cpu" "$1"/$5 --threads "$3" $quiet_output --out "$out/o" > "$out/log" 2>&1
    awk -v name="$4" -v build="$2" -v threads="$3" -v cpu="$(awk '{ print $1 + $2 }' "$out/cpu")" '
        /^RESULT/ { for (i = 1; i <= NF; ++i) { split($i, kv, "="); v[kv[1]] = kv[2] } }
        END { n = v["particles"] * v["steps"]; printf "%s %s %s %.1f %.1f\n", name, build, threads, v["wall_s"] * 1e9 / n, cpu * 1e9 / n }' \
        "$out/log" >> "$out/times"
}
builds="old"
[ -n "$new" ] && builds="old new"
r=1
while [ "$r" -le "$rounds" ]; do
    for threads in $threads_list; do
        echo "$cases" | while IFS='|' read -r name cmd; do
            order=$builds
            [ $((r % 2)) -eq 0 ] && [ -n "$new" ] && order="new old"
            for build in $order; do
                dir=$old
                [ "$build" = new ] && dir=$new
                run "$dir" "$build" "$threads" "$name" "$cmd"
            done
        done
    done
    r=$((r + 1))
done
# medians; the one-thread figure is the CPU time's, the two-thread one the wall time's
awk -v rounds="$rounds" '
    function median(key,    m, i, j, x, a) {
        m = n[key]; for (i = 1; i <= m; ++i) a[i] = t[key, i]
        for (i = 1; i <= m; ++i) for (j = i + 1; j <= m; ++j) if (a[j] < a[i]) { x = a[i]; a[i] = a[j]; a[j] = x }
        return m % 2 ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2
    }
    { key = $1 " " $2 " " $3; t[key, ++n[key]] = $3 == 1 ? $5 : $4; seen[$2 " " $3] = 1 }
    END {
        printf "ns per particle and sub-step, medians of %d interleaved rounds (1 thread: CPU time; 2 threads: wall time)\n", rounds
        printf "%-6s %-8s %10s %10s %16s\n", "build", "threads", "granular", "elastic", "granular/elastic"
        for (bt in seen) {
            split(bt, p, " "); g = median("granular " bt); e = median("elastic " bt)
            printf "%-6s %-8s %10.1f %10.1f %16.3f\n", p[1], p[2], g, e, g / e
            ratio[bt] = g / e; gran[bt] = g; elas[bt] = e
        }
        for (bt in seen) {
            split(bt, p, " ")
            if (p[1] == "new" && ("old " p[2]) in seen)
                printf "new/old, %s thread(s): granular %.3f, elastic %.3f\n", p[2], gran[bt] / gran["old " p[2]], elas[bt] / elas["old " p[2]]
        }
        for (bt in seen) {
            split(bt, p, " ")
            printf "RESULT case=granular_vs_elastic build=%s threads=%s granular_ns=%.1f elastic_ns=%.1f ratio=%.3f target=2 rounds=%d\n",
                   p[1], p[2], gran[bt], elas[bt], ratio[bt], rounds
        }
    }' "$out/times"
