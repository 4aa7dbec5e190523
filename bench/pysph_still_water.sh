#!/bin/sh
# pysph_still_water.sh - PySPH's own hydrostatic tank (pysph.examples.hydrostatic_tank: Adami walls,
# artificial viscosity alpha 0.24, gravity ramped over 1 s) run to t = 10 s and measured like
# bench/still_water.c: worst one-second RMS and largest fluid speed over 5-10 s, in sqrt(g H).
#
# Usage: sh bench/pysph_still_water.sh            depth/dp 45 (the example's own resolution, ~5 min)
#        PYSPH_90=1 sh bench/pysph_still_water.sh  also depth/dp 90 (8x the work)
# Runs single-threaded and niced; needs Debian's python3-pysph (installed here if missing, as root).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
PY=/usr/bin/python3

# 1. PySPH: Debian's package (it also pulls in cython3 and a C compiler: PySPH compiles its kernels).
if ! $PY -c 'import pysph' 2>/dev/null; then
    if ! command -v apt-get >/dev/null 2>&1 || [ "$(id -u)" != 0 ]; then
        echo "pysph_still_water: python3-pysph is not installed and apt-get (as root) is unavailable: skipped"
        exit 0
    fi
    export DEBIAN_FRONTEND=noninteractive
    if ! { apt-get update -qq && apt-get install -y -qq --no-install-recommends python3-pysph; } >/dev/null 2>&1; then
        echo "pysph_still_water: could not install python3-pysph with apt-get: skipped"
        exit 0
    fi
fi

# 2. One case: run the example into a temp dir, then post-process its output files.
run_case() {
    out=$(mktemp -d "${TMPDIR:-/tmp}/pysph_still_water.XXXXXX")
    start=$(date +%s)
    # one thread, low priority: the machine is shared
    OMP_NUM_THREADS=1 nice -n 10 $PY "$here/pysph_still_water.py" run "$1" "$out" > "$out/run.log" 2>&1 ||
        { tail -20 "$out/run.log"; echo "pysph_still_water: PySPH run failed (log: $out/run.log)"; exit 1; }
    wall=$(( $(date +%s) - start ))
    grep '^# example' "$out/run.log" || true
    $PY "$here/pysph_still_water.py" post "$1" "$out" "$wall"
    rm -rf "$out"
}

run_case 45
if [ "${PYSPH_90:-0}" = 1 ]; then run_case 90; fi
