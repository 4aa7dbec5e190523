#!/bin/sh
# Our 2D plate against the peers a user can install from the machine's package manager, in
# interleaved rounds on this machine. Today one peer: PySPH (Debian: apt install python3-pysph),
# whose examples/solid_mech/oscillating_plate.py is our benchmark A1 (L 0.2, H 0.02, H/dp 10,
# E 2e6, nu 0.3975, rho0 1000, v_f 0.05) with Gray et al.'s artificial stress, the cubic spline,
# Monaghan's artificial viscosity and XSPH at a fixed dt of 1e-5 s. Equal formulation on our
# side: --shear oas --kernel spline (Gray's artificial stress, the cubic spline), built with
# every pair loop instanced (build/all_loops: the spline's loops vectorised, as the Wendland
# kernel's are by default); also our default (ENO-A, Wendland), and the plate as a
# total-Lagrangian body (TL's default hourglass control, alpha 50). A peer that is missing is
# skipped.
# The reference code (SPHinXsys, the papers' code) is not in the package manager: its figures
# (bench/results/sphinxsys_reference.csv, with the CPU they were measured on) are
# printed next to ours, measured again here on the same cases (2 threads, best of the rounds);
# the ratio holds for that CPU kind only.
#   sh bench/side_by_side.sh                 t = 0.05 s, 3 rounds, 1 and 2 threads, then the
#                                            reference cases (about 3 + 3 min on a quiet machine)
#   TEND=0.1 ROUNDS=5 THREADS="2" REFERENCE=0 sh bench/side_by_side.sh
# Writes bench/results/$MACHINE/side_by_side.csv (every run) and side_by_side.md (the best of
# the rounds, and the ratios: the peer's wall time over ours for the same simulated time, and per
# particle-step). PySPH's time is its own "Run took" (without its set-up and code generation).
set -eu
cd "$(dirname "$0")/.."
MACHINE=${MACHINE:-c-2core-xeon}
TEND=${TEND:-0.05}
ROUNDS=${ROUNDS:-3}
THREADS=${THREADS:-"1 2"}
OUT=bench/results/$MACHINE
TMP=${TMPDIR:-/tmp}/side_by_side_$$
mkdir -p "$OUT" "$TMP"
CSV=$OUT/side_by_side.csv
MD=$OUT/side_by_side.md
REFERENCE=${REFERENCE:-1}
REF=${REF:-bench/results/sphinxsys_reference.csv}
REF_MD=$OUT/side_by_side_reference.md
make -s build/plate2d build/all_loops/plate2d build/spinning_plate build/column_collapse2d

# the Python that has PySPH: Debian's package installs it for /usr/bin/python3
PY=""
for p in python3 /usr/bin/python3; do
    if command -v "$p" >/dev/null 2>&1 && "$p" -c 'import pysph' >/dev/null 2>&1; then PY=$p; break; fi
done
PLATE=""
if [ -n "$PY" ]; then
    PLATE=$("$PY" -c 'import os, pysph; print(os.path.join(os.path.dirname(pysph.__file__), "examples", "solid_mech", "oscillating_plate.py"))')
    [ -f "$PLATE" ] || PLATE=""
fi
[ -n "$PLATE" ] || echo "PySPH not found (Debian: apt install python3-pysph): skipped; only our rows are written"

field() { echo "$2" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
echo "round,code,formulation,threads,particles,steps,wall_s,ns_per_particle_step" > "$CSV"

pysph_run() { # round threads
    OMP_NUM_THREADS=$2 "$PY" "$PLATE" --tf "$TEND" --openmp --disable-output -d "$TMP/pysph" > "$TMP/pysph.log" 2>&1
    wall=$(sed -n 's/^Run took: \([0-9.e+-]*\) secs/\1/p' "$TMP/pysph.log")
    n=$(sed -n 's/^  Total: //p' "$TMP/pysph.log")
    steps=$(awk -v t="$TEND" 'BEGIN { printf "%d", t / 1e-5 + 0.5 }') # the example's fixed dt
    echo "$1,pysph,gray artificial stress + cubic spline (dt 1e-5),$2,$n,$steps,$wall,$(awk -v w="$wall" -v n="$n" -v s="$steps" 'BEGIN { printf "%.1f", 1e9 * w / (n * s) }')" >> "$CSV"
}
ours_run() { # binary round threads label args...
    bin=$1 r=$2 thr=$3 label=$4; shift 4
    line=$($bin --quiet --tend "$TEND" --threads "$thr" --vtk-every 0 --csv-every 1 --out "$TMP/ours" "$@" | grep '^RESULT')
    n=$(field particles "$line") steps=$(field steps "$line") wall=$(field wall_s "$line")
    echo "$r,sphsolid,$label,$thr,$n,$steps,$wall,$(awk -v w="$wall" -v n="$n" -v s="$steps" 'BEGIN { printf "%.1f", 1e9 * w / (n * s) }')" >> "$CSV"
}

# PySPH generates and compiles its code on the first run: once, untimed
[ -z "$PLATE" ] || OMP_NUM_THREADS=1 "$PY" "$PLATE" --tf 1e-4 --openmp --disable-output -d "$TMP/pysph" > /dev/null 2>&1
r=1
while [ "$r" -le "$ROUNDS" ]; do
    for thr in $THREADS; do
        [ -z "$PLATE" ] || pysph_run "$r" "$thr"
        ours_run ./build/all_loops/plate2d "$r" "$thr" "gray artificial stress + cubic spline (oas)" --shear oas --kernel spline
        ours_run ./build/plate2d "$r" "$thr" "default (eno-a + wendland)"
        ours_run ./build/plate2d "$r" "$thr" "total Lagrangian (saint venant-kirchhoff, hourglass alpha 50)" --solver tl
    done
    r=$((r + 1))
done

# the reference code's cases: ours again, interleaved by round, 2 threads
if [ "$REFERENCE" = 1 ]; then
    echo "round,case,wall_s" > "$TMP/ref.csv"
    r=1
    while [ "$r" -le "$ROUNDS" ]; do
        grep -v '^#' "$REF" | tail -n +2 | while IFS=, read -r case rcase rn rwall cmd on owall rcpu; do
            line=$(./build/$cmd --threads 2 --quiet --vtk-every 0 --png-every 0 --out "$TMP/ref" | grep '^RESULT')
            echo "$r,$case,$(field wall_s "$line")" >> "$TMP/ref.csv"
        done
        r=$((r + 1))
    done
fi
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -1)
if [ "$REFERENCE" = 1 ]; then
    {
        echo "<!-- generated by sh bench/side_by_side.sh; do not edit -->"
        echo "The reference code's figures (SPHinXsys, 2 threads, quiet machine; $REF) against ours on this machine"
        echo "(CPU: ${cpu:-unknown}; 2 threads, best of $ROUNDS rounds). The ratio compares like with like only on the CPU kind of the reference figures."
        echo
        echo "| case | reference code's case | reference [s] | CPU of the reference figures | ours at filing [s] | ours now [s] (best; all rounds) | reference / ours now |"
        echo "|---|---|---|---|---|---|---|"
        grep -v '^#' "$REF" | tail -n +2 | while IFS=, read -r case rcase rn rwall cmd on owall rcpu; do
            best=$(awk -F, -v c="$case" '$2 == c && (b == "" || $3 + 0 < b + 0) { b = $3 } END { print b }' "$TMP/ref.csv")
            all=$(awk -F, -v c="$case" '$2 == c { s = s (s == "" ? "" : " / ") $3 } END { print s }' "$TMP/ref.csv")
            awk -v c="$case" -v rc="$rcase" -v rw="$rwall" -v cpu="$rcpu" -v ow="$owall" -v b="$best" -v a="$all" -v cmd="$cmd" \
                'BEGIN { printf "| %s (`%s`) | %s | %s | %s | %s | %s (%s) | %.1fx |\n", c, cmd, rc, rw, cpu, ow, b, a, (b > 0 ? rw / b : 0) }'
        done
    } > "$REF_MD"
fi
rm -rf "$TMP"
{
    echo "<!-- generated by sh bench/side_by_side.sh; do not edit -->"
    echo "CPU: ${cpu:-unknown}; 2D plate (A1), H/dp 10, to t = $TEND s; best of $ROUNDS interleaved rounds."
    echo
    echo "| code | formulation | threads | particles | steps | wall [s] (best; all rounds) | ns / particle-step | peer's wall / ours | peer's ns / ours |"
    echo "|---|---|---|---|---|---|---|---|---|"
    awk -F, 'NR > 1 {
        key = $2 "|" $3 "|" $4
        if (!(key in best) || $7 + 0 < best[key] + 0) { best[key] = $7; ns[key] = $8; n[key] = $5; st[key] = $6 }
        if (!(key in seen)) { seen[key] = 1; order[++count] = key; all[key] = $7 } else all[key] = all[key] " / " $7
        if ($2 == "pysph") {
            if (!($4 in pw) || $7 + 0 < pw[$4] + 0) pw[$4] = $7
            if (!($4 in pn) || $8 + 0 < pn[$4] + 0) pn[$4] = $8
        }
    } END {
        for (c = 1; c <= count; ++c) {
            key = order[c]; split(key, f, "|")
            ratio = "-"; rns = "-"
            if (f[1] != "pysph" && (f[3] in pw)) { ratio = sprintf("%.1fx", pw[f[3]] / best[key]); rns = sprintf("%.1fx", pn[f[3]] / ns[key]) }
            printf "| %s | %s | %s | %s | %s | %s (%s) | %s | %s | %s |\n", f[1], f[2], f[3], n[key], st[key], best[key], all[key], ns[key], ratio, rns
        }
    }' "$CSV"
} > "$MD"
cat "$MD"
echo "written $CSV and $MD"
if [ "$REFERENCE" = 1 ]; then cat "$REF_MD"; echo "written $REF_MD"; fi
