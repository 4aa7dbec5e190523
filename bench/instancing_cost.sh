#!/bin/sh
# The speed of two builds of the examples, run interleaved (old, new, new, old, ...) so that a
# machine whose load drifts treats both alike: the wall time per particle and sub-step of the 2D
# plate (ENO-A and GNO-A), the 3D plate and the column collapse, --threads 1 and 2, ROUNDS rounds,
# the median of each and the ratio new / old (bench/VALIDATION.md, "Instancing"); any two
# builds of the examples serve.
#   bench/instancing_cost.sh OLD_BUILD_DIR NEW_BUILD_DIR [ROUNDS]
# e.g. make build/plate2d build/plate3d build/column_collapse2d in each tree, then
#   bench/instancing_cost.sh /tmp/base/build build 3
# The cases' lengths (TEND_*) keep one run at a few seconds on one core; longer ones can be set
# in the environment, and THREADS (default "1 2"). The medians mean something only on a quiet
# machine: two threads on two cores that others use wait at every barrier.
set -eu
old=${1:?old build dir}
new=${2:?new build dir}
rounds=${3:-3}
threads_list=${THREADS:-1 2}
tend_plate2d=${TEND_PLATE2D:-0.2}
tend_plate3d=${TEND_PLATE3D:-0.0005}
tend_column=${TEND_COLUMN:-0.02}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cases="plate2d_eno-a|plate2d --res 10 --tend $tend_plate2d --shear eno-a
plate2d_gno-a|plate2d --res 10 --tend $tend_plate2d --shear gno-a
plate3d|plate3d --res 3 --tend $tend_plate3d
column_collapse2d|column_collapse2d --tend $tend_column"
# ns per particle and sub-step from an example's RESULT line (wall_s, particles, steps), by its
# wall time and by the CPU time /usr/bin/time measured (user + system, all threads: on a loaded
# machine the CPU time of one thread is the steadier figure, as a run waiting for a core does
# not count)
ns_of() {
    awk '/^RESULT/ { for (i = 1; i <= NF; ++i) { split($i, kv, "="); v[kv[1]] = kv[2] } }
         /^cpu_s=/ { split($0, kv, "="); cpu = kv[2] }
         END { n = v["particles"] * v["steps"]; printf "%.1f %.1f\n", v["wall_s"] * 1e9 / n, cpu * 1e9 / n }' "$1"
}
run() { # build dir, label, threads, command line -> appends "label threads wall_ns cpu_ns" to $out/times
    # shellcheck disable=SC2086
    /usr/bin/time -f "cpu_s=%U %S" -o "$out/cpu" "$1"/$4 --threads "$3" --quiet --vtk-every 0 --out "$out/o" > "$out/log" 2>&1
    awk '{ split($1, kv, "="); printf "cpu_s=%.3f\n", kv[2] + $2 }' "$out/cpu" >> "$out/log"
    echo "$2 $3 $(ns_of "$out/log")" >> "$out/times"
}
r=1
while [ "$r" -le "$rounds" ]; do
    for threads in $threads_list; do
        echo "$cases" | while IFS='|' read -r name cmd; do
            if [ $((r % 2)) -eq 1 ]; then
                run "$old" "$name:old" "$threads" "$cmd"; run "$new" "$name:new" "$threads" "$cmd"
            else
                run "$new" "$name:new" "$threads" "$cmd"; run "$old" "$name:old" "$threads" "$cmd"
            fi
        done
    done
    r=$((r + 1))
done
echo "case threads old_wall_ns new_wall_ns new/old old_cpu_ns new_cpu_ns new/old (medians of $rounds interleaved rounds; ns per particle and sub-step)"
awk -f "$(dirname "$0")/medians.awk" "$out/times" | awk '
    { split($1, c, ":"); k = c[1] " " $2 }
    c[2] == "old" { ow[k] = $3; oc[k] = $4 }
    c[2] == "new" { nw[k] = $3; nc[k] = $4 }
    END { for (k in ow) printf "%s %.1f %.1f %.3f %.1f %.1f %.3f\n", k, ow[k], nw[k], nw[k] / ow[k], oc[k], nc[k], nc[k] / oc[k] }' | sort
