#!/bin/sh
# ANG Table 1: first period of the 2D plate (benchmark A1, bench/VALIDATION.md) for the six shear formulations
# and v_f = 0.001, 0.01, 0.03, 0.05, next to the paper's values. Writes
# bench/results/$MACHINE/table1.csv (one row per run; rows already there are kept, so an
# interrupted sweep resumes) and prints the table in markdown.
#   sh bench/table1.sh                    H/dp = 30 (the paper's), about 2 h on one core
#   RES=10 sh bench/table1.sh             a quick look (about 4 min)
#   THREADS=2 SHEARS="gno-a eno-a" sh bench/table1.sh
#   SHEARS="eno-a:pair gno-a:pair" sh bench/table1.sh   the -A variants with --rotation pair
#   REPORT=1 RES=30 sh bench/table1.sh   print the table from the CSV, run nothing
set -eu
cd "$(dirname "$0")/.."
MACHINE=${MACHINE:-c-2core-xeon} # the results folder of the machine the README reports; set MACHINE on another
RES=${RES:-30}
THREADS=${THREADS:-1}
# the first period is the second zero crossing: 0.32 s covers 0.25-0.30 s (H/dp >= 20); coarser
# plates swing slower
if [ "$RES" -ge 20 ]; then TEND=${TEND:-0.32}; else TEND=${TEND:-0.4}; fi
SHEARS=${SHEARS:-"gno-a eno-a eno gno oas og"}
VFS="0.001 0.01 0.03 0.05"
BIN=${BIN:-./build/plate2d}
OUT=bench/results/$MACHINE
CSV=$OUT/table1.csv
mkdir -p "$OUT"
[ -n "${BIN_GIVEN:-}" ] || [ "${REPORT:-0}" = 1 ] || make -s examples
[ -f "$CSV" ] || echo "res,shear,vf,period,paper,err_paper_pct,err_analytical_pct,hourglass_max,wall_s" > "$CSV"

field() { echo "$2" | tr ' ' '\n' | sed -n "s/^$1=//p"; }

for spec in $SHEARS; do
    [ "${REPORT:-0}" = 1 ] && break
    shear=${spec%%:*}                                          # "eno-a:pair" -> eno-a, rotation pair
    rotation=mean; case $spec in *:*) rotation=${spec#*:} ;; esac
    for vf in $VFS; do
        if grep -q "^$RES,$spec,$vf," "$CSV"; then continue; fi
        line=$("$BIN" --quiet --res "$RES" --shear "$shear" --rotation "$rotation" --vf "$vf" --tend "$TEND" --threads "$THREADS" \
               --vtk-every 0 --csv-every 0.0005 --out "out/table1_${shear}_${rotation}_$vf" | grep '^RESULT' || true)
        if [ -z "$line" ]; then echo "$RES,$spec,$vf,stopped,,,,," >> "$CSV"; continue; fi
        echo "$RES,$spec,$vf,$(field period "$line"),$(field paper "$line"),$(field err_paper "$line" | tr -d %),$(field err_analytical "$line" | tr -d %),$(field hourglass_max "$line"),$(field wall_s "$line")" | tee -a "$CSV"
    done
done

echo
echo "First period [s] at H/dp = $RES, ours (paper, ANG Table 1); analytical 0.2541 s"
echo
echo "| formulation | v_f = 0.001 | 0.01 | 0.03 | 0.05 |"
echo "|---|---|---|---|---|"
for spec in $SHEARS; do
    row="| $spec |"
    for vf in $VFS; do
        cell=$(awk -F, -v r="$RES" -v s="$spec" -v v="$vf" '$1==r && $2==s && $3==v {
            if ($4 == "stopped" || $4 < 0) printf "none"; else printf "%s", $4;
            if ($5 != "" && $5 > 0) printf " (%s)", $5 }' "$CSV")
        row="$row ${cell:-n/a} |"
    done
    echo "$row"
done
