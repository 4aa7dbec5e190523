#!/bin/sh
# What the implementation costs to compile: examples/impl.c, the whole library in one translation
# unit, compiled ROUNDS times as the full build and as the elastic-only build (every compile-out
# switch), the median user CPU time of each (the compiler is one thread: its user time is the
# steadiest figure on a machine that others use too), the object's text size, and the pair
# loops in it (bench/VALIDATION.md, "Compile cost"): their count and bytes, of all functions'.
#   bench/compile_cost.sh [ROUNDS] [OLD_TREE]
# With OLD_TREE (another checkout of the library, e.g. `git worktree add /tmp/old main`), its
# header is compiled too, alternating with this one's in every round, and the table gets its
# columns and the ratio new / old. CC (default cc) and CFLAGS (default the acceptance's
# -std=c99 -O2 -fopenmp; the Makefile's add -march=native and its tuning) in the environment.
set -eu
rounds=${1:-3}
old=${2:-}
here=$(cd "$(dirname "$0")/.." && pwd)
cc=${CC:-cc}
cflags=${CFLAGS:--std=c99 -O2 -fopenmp}
elastic="-DSPHSOLID_NO_FLUID -DSPHSOLID_NO_GRANULAR -DSPHSOLID_NO_PLASTICITY -DSPHSOLID_NO_TOTAL_LAGRANGIAN -DSPHSOLID_NO_GEOMETRY"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# compile TREE LABEL BUILD_FLAGS: one compile of TREE's examples/impl.c; appends "LABEL user_s" to $out/times
compile() {
    # shellcheck disable=SC2086
    /usr/bin/time -f "%U" -o "$out/user" $cc $cflags $3 -c "$1/examples/impl.c" -o "$out/$2.o"
    echo "$2 $(cat "$out/user")" >> "$out/times"
}
# sizes LABEL: text bytes, all functions' bytes, pair-loop functions (sps__*_pairs_*) and their bytes
sizes() {
    text=$(size "$out/$1.o" | awk 'NR == 2 { print $1 }')
    nm -S -t d "$out/$1.o" | awk -v text="$text" '
        NF == 4 && ($3 == "t" || $3 == "T") { all += $2; if ($4 ~ /^sps__[a-z_]*_pairs_/) { n += 1; pairs += $2 } }
        END { printf "%d %d %d %d", text, all, n, pairs }'
}
r=1
while [ "$r" -le "$rounds" ]; do
    for build in full elastic; do
        flags=""
        [ "$build" = elastic ] && flags=$elastic
        if [ -n "$old" ] && [ $((r % 2)) -eq 1 ]; then compile "$old" "$build:old" "$flags"; fi
        compile "$here" "$build:new" "$flags"
        if [ -n "$old" ] && [ $((r % 2)) -eq 0 ]; then compile "$old" "$build:old" "$flags"; fi
    done
    r=$((r + 1))
done
echo "$cc $cflags -c examples/impl.c; medians of $rounds rounds$([ -n "$old" ] && echo ", alternating with $old")"
echo "build tree user_s text_B functions_B pair_loops pair_loop_B"
for build in full elastic; do
    for tree in old new; do
        grep -q "^$build:$tree " "$out/times" || continue
        user=$(awk -v k="$build:$tree" '$1 == k { print $2 }' "$out/times" | sort -n |
               awk '{ v[NR] = $1 } END { print NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }')
        echo "$build $tree $user $(sizes "$build:$tree")"
    done
done | awk '{ print } $2 == "old" { o[$1] = $3 } $2 == "new" && o[$1] { printf "%s new/old %.3f\n", $1, $3 / o[$1] }'
