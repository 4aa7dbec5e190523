#!/bin/sh
# restore_cost.sh - what checking an untrusted restart file costs: bench/io_cost.c built against
# this header and against another one (OLD, e.g. the header before the checks: git show
# e20f9f4:sphsolid.h), run in interleaved rounds on the 2D plate; the medians of their restore
# (and save) times, and the ratio. bench/VALIDATION.md, "Untrusted files".
# Usage: sh bench/restore_cost.sh OLD_TREE [ROUNDS] [RES ...]   (OLD_TREE: a checkout holding the old
#        sphsolid.h, examples/ and bench/io_cost.c; default 7 rounds, H/dp 10 and 30, t = 0.01 s, one thread)
set -eu
old=$1; rounds=${2:-7}; shift; [ $# -gt 0 ] && shift
res=${*:-10 30}
out=build/restore_cost; mkdir -p "$out"
flags="-std=c99 -O2 -march=native -fno-math-errno -fno-trapping-math -fopenmp"
cc $flags bench/io_cost.c -o "$out/io_new" -lm
(cd "$old" && cc $flags bench/io_cost.c -o "$OLDPWD/$out/io_old" -lm)
: > "$out/times"
for r in $(seq "$rounds"); do
    for n in $res; do
        for v in old new; do
            "./$out/io_$v" --res "$n" --tend 0.01 --threads 1 --repeat 10 --out "$out/files_$v" |
              sed -n 's/.*save_ms=\([0-9.]*\) restore_ms=\([0-9.]*\).*/\1 \2/p' | sed "s/^/res$n $v /" >> "$out/times"
        done
    done
done
awk -f bench/medians.awk "$out/times" | sort | awk '
    { save[$1, $2] = $3; restore[$1, $2] = $4; names[$1] = 1 }
    END { print "| H/dp | restore old [ms] | restore new [ms] | ratio | save old [ms] | save new [ms] |"
          print "|---|---|---|---|---|---|"
          for (k in names) printf "| %s | %.3f | %.3f | %.2fx | %.3f | %.3f |\n", substr(k, 4), restore[k, "old"], restore[k, "new"],
                                  restore[k, "new"] / restore[k, "old"], save[k, "old"], save[k, "new"] }'
