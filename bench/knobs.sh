#!/bin/sh
# What each setting costs and what it buys: one knob at a time around a default, on the 2D plate
# (first period against thin-plate theory, 0.2541 s), the spinning plate (angular-momentum
# error), the 3D plate at H/dp = 3 (cost; first period of mode (2,2) in double and float) and the
# real-time loop (bench/realtime.c). Writes to bench/results/$MACHINE/:
#   knobs.csv              one row per run (columns below)
#   knobs.md               the tables of README "Choosing settings" and bench/VALIDATION.md
#   knobs_plate2d.svg      2D plate: CPU time vs |period error|, with the Pareto front
#   knobs_spinning.svg     spinning plate: CPU time vs angular-momentum error per formulation
#
#   sh bench/knobs.sh            the sweep (about 15 min on 2 busy cores), then the report
#   sh bench/knobs.sh report     the report again from knobs.csv (no runs)
#   RESUME=1 sh bench/knobs.sh   keep the rows already in knobs.csv (an interrupted sweep)
#
# Defaults: 2D plate H/dp 10, v_f 0.05, ENO-A, dual stepping, CFL_ac 0.4, recomputed geometry,
# Wendland, double, 1 thread, to t = 0.3 s (the first period ends near 0.26 s); spinning plate
# dp 0.05, GNO-A, to t = 0.5 s (ANG's horizon) for every point. Every run is niced and alone, with
# 1 thread except the threads knob. The machine may be shared, so the cost is the CPU time
# (user + sys of the process, from `time -p`); ns per particle-step = CPU time / (particles x
# acoustic sub-steps) for 1-thread runs. Energy drift: last vs first total energy in the run's CSV.
set -eu
cd "$(dirname "$0")/.."
MACHINE=${MACHINE:-c-2core-xeon} # the results folder of the machine the README reports; set MACHINE on another
OUT=bench/results/$MACHINE
CSV=$OUT/knobs.csv
TIMER=${TIMER:-/usr/bin/time} # any POSIX time utility with -p
RUNS=out/knobs
# OpenMP threads spin at barriers by default; on a shared machine that costs whole time slices
# (bench/VALIDATION.md, design notes)
export OMP_WAIT_POLICY=passive
COLUMNS_CSV="scene,knob,setting,real,res,shear,stepping,cfl,geometry,kernel,threads,t_end,particles,acoustic_steps,wall_s,user_s,sys_s,cpu_s,ns_cpu,period_s,period_err_pct,angmom_err_pct,energy_drift_pct,sim_per_wall,status"

# field KEY FILE: the value of key=value in the RESULT line of FILE
field() { sed -n 's/^RESULT //p' "$2" | tr ' ' '\n' | sed -n "s/^$1=//p" | tr -d '%'; }

# energy_drift FILE: 100 (E_last - E_first) / E_first of the total_energy column
energy_drift() {
    [ -f "$1" ] || return 0
    awk -F, 'NR == 1 { for (k = 1; k <= NF; ++k) if ($k == "total_energy") c = k; next }
             NR == 2 { first = $c } { last = $c }
             END { if (c && first != 0) printf "%.4g", 100 * (last - first) / first }' "$1"
}

# run SCENE KNOB SETTING REAL RES SHEAR STEPPING CFL GEOMETRY KERNEL THREADS TEND [ARGS...]
# REAL: double or float (build/float/); RES: H/dp for the plates, dp for the spinning plate.
run() {
    scene=$1 knob=$2 setting=$3 real=$4 res=$5 shear=$6 stepping=$7 cfl=$8 geometry=$9
    shift 9
    kernel=$1 threads=$2 tend=$3
    shift 3
    if [ "${RESUME:-0}" = 1 ] && grep -q "^$scene,$knob,$setting,$real," "$CSV"; then return 0; fi
    dir=$RUNS/$(echo "$scene-$knob-$setting-$real" | tr -c 'A-Za-z0-9.\n-' '_')
    mkdir -p "$dir"
    bin=build/$scene
    [ "$real" = float ] && bin=build/float/$scene
    case $scene in spinning_plate | realtime) size="--dp $res" ;; *) size="--res $res" ;; esac
    status=ok
    # shellcheck disable=SC2086 # $size is two words on purpose
    nice -n 5 "$TIMER" -p "$bin" --quiet $size --shear "$shear" --stepping "$stepping" --cfl "$cfl" --geometry "$geometry" \
        --kernel "$kernel" --threads "$threads" --tend "$tend" --vtk-every 0 --out "$dir" "$@" > "$dir/stdout" 2> "$dir/stderr" ||
        status=failed
    user=$(sed -n 's/^user //p' "$dir/stderr")
    sys=$(sed -n 's/^sys //p' "$dir/stderr")
    wall=$(sed -n 's/^real //p' "$dir/stderr")
    n=$(field particles "$dir/stdout")
    steps=$(field steps "$dir/stdout")
    period="" err="" angmom="" ratio=""
    case $scene in
    plate2d | plate3d)
        period=$(field period "$dir/stdout")
        analytical=$(field analytical "$dir/stdout")
        if [ -n "$period" ] && awk "BEGIN { exit !($period > 0) }"; then
            err=$(awk "BEGIN { printf \"%.4g\", 100 * ($period - $analytical) / $analytical }")
        else
            period=""
            # the 2D plate always runs past its first period; the short 3D runs do not
            if [ "$scene" = plate2d ] && [ "$status" = ok ]; then status=no_period; fi
        fi ;;
    spinning_plate) angmom=$(field max_angmom_err "$dir/stdout") ;;
    realtime) angmom=$(field max_angmom_err "$dir/stdout"); ratio=$(field sim_per_wall "$dir/stdout") ;;
    esac
    drift=$(energy_drift "$dir/$scene.csv")
    cpu=$(awk "BEGIN { printf \"%.2f\", ${user:-0} + ${sys:-0} }")
    ns=""
    if [ "$threads" = 1 ] && [ -n "$n" ] && [ -n "$steps" ]; then ns=$(awk "BEGIN { printf \"%.1f\", 1e9 * $cpu / ($n * $steps) }"); fi
    echo "$scene,$knob,$setting,$real,$res,$shear,$stepping,$cfl,$geometry,$kernel,$threads,$tend,$n,$steps,$wall,$user,$sys,$cpu,$ns,$period,$err,$angmom,$drift,$ratio,$status" |
        tee -a "$CSV"
}

# plate2d KNOB SETTING REAL RES SHEAR STEPPING CFL GEOMETRY KERNEL THREADS
plate2d() { run plate2d "$@" 0.3 --csv-every 0.002; }
# spinning KNOB SETTING REAL DP SHEAR STEPPING CFL GEOMETRY KERNEL THREADS
spinning() { run spinning_plate "$@" 0.5; }
# plate3d_short KNOB SETTING REAL STEPPING CFL GEOMETRY KERNEL THREADS: 0.002 s (335 sub-steps)
plate3d_short() { run plate3d "$1" "$2" "$3" 3 eno-a "$4" "$5" "$6" "$7" "$8" 0.002 --mode 2,2 --full --csv-every 0.0001; }
# realtime SETTING REAL DP GEOMETRY BUDGET: 60 frames per second to t = 0.5 s
realtime() { run realtime loop "$1" "$2" "$3" gno-a dual 0.4 "$4" wendland 1 0.5 --fps 60 --budget "$5"; }

sweep() {
    mkdir -p "$OUT" "$RUNS"
    if [ "${RESUME:-0}" != 1 ] || [ ! -f "$CSV" ]; then echo "$COLUMNS_CSV" > "$CSV"; fi
    make -s examples float-examples bench-tools

    plate2d default default double 10 eno-a dual 0.4 recomputed wendland 1
    for res in 5 20; do plate2d resolution "H/dp $res" double "$res" eno-a dual 0.4 recomputed wendland 1; done
    for shear in eno og oas gno gno-a; do plate2d shear "$shear" double 10 "$shear" dual 0.4 recomputed wendland 1; done
    plate2d stepping single double 10 eno-a single 0.4 recomputed wendland 1
    for cfl in 0.2 0.6 0.8; do plate2d cfl "CFL $cfl" double 10 eno-a dual "$cfl" recomputed wendland 1; done
    plate2d geometry frozen double 10 eno-a dual 0.4 frozen wendland 1
    for res in 5 10 20; do plate2d real "float H/dp $res" float "$res" eno-a dual 0.4 recomputed wendland 1; done
    plate2d kernel spline double 10 eno-a dual 0.4 recomputed spline 1
    plate2d threads "2 threads" double 10 eno-a dual 0.4 recomputed wendland 2
    # the -A variants' stored increments kept per pair (0.4.0), with and without stress output
    run plate2d rotation pair double 10 eno-a dual 0.4 recomputed wendland 1 0.3 --csv-every 0.002 --rotation pair
    run plate2d rotation "pair+stress off" double 10 eno-a dual 0.4 recomputed wendland 1 0.3 --csv-every 0.002 --rotation pair --stress off
    # combinations: what the cheap knobs give together (candidates for the presets)
    plate2d combined "frozen+float" float 10 eno-a dual 0.4 frozen wendland 1
    plate2d combined "frozen+float+CFL 0.6" float 10 eno-a dual 0.6 frozen wendland 1
    plate2d combined "H/dp 5 frozen+float+CFL 0.6" float 5 eno-a dual 0.6 frozen wendland 1
    plate2d combined "H/dp 20 CFL 0.6" double 20 eno-a dual 0.6 recomputed wendland 1
    plate2d combined "H/dp 20 float+CFL 0.6" float 20 eno-a dual 0.6 recomputed wendland 1
    plate2d combined "H/dp 20 frozen+CFL 0.6" double 20 eno-a dual 0.6 frozen wendland 1
    plate2d combined "H/dp 20 frozen+float+CFL 0.6" float 20 eno-a dual 0.6 frozen wendland 1

    for dp in 0.1 0.05 0.033; do
        for shear in gno-a eno-a eno gno oas og; do
            knob=shear
            [ "$dp" = 0.05 ] || knob=resolution
            [ "$dp" = 0.05 ] && [ "$shear" = gno-a ] && knob=default
            spinning "$knob" "$shear dp $dp" double "$dp" "$shear" dual 0.4 recomputed wendland 1
        done
    done
    spinning stepping single double 0.05 gno-a single 0.4 recomputed wendland 1
    for cfl in 0.2 0.6 0.8; do spinning cfl "CFL $cfl" double 0.05 gno-a dual "$cfl" recomputed wendland 1; done
    spinning geometry frozen double 0.05 gno-a dual 0.4 frozen wendland 1
    for shear in gno-a eno-a; do spinning real "float $shear" float 0.05 "$shear" dual 0.4 recomputed wendland 1; done
    spinning kernel spline double 0.05 gno-a dual 0.4 recomputed spline 1
    spinning threads "2 threads" double 0.05 gno-a dual 0.4 recomputed wendland 2
    run spinning_plate rotation "eno-a pair" double 0.05 eno-a dual 0.4 recomputed wendland 1 0.5 --rotation pair
    run spinning_plate rotation "eno-a pair+stress off" double 0.05 eno-a dual 0.4 recomputed wendland 1 0.5 --rotation pair --stress off
    spinning combined "frozen+float+CFL 0.6" float 0.05 gno-a dual 0.6 frozen wendland 1

    plate3d_short default default double dual 0.4 recomputed wendland 1
    plate3d_short stepping single double single 0.4 recomputed wendland 1
    for cfl in 0.2 0.6 0.8; do plate3d_short cfl "CFL $cfl" double dual "$cfl" recomputed wendland 1; done
    plate3d_short geometry frozen double dual 0.4 frozen wendland 1
    plate3d_short real float float dual 0.4 recomputed wendland 1
    plate3d_short kernel spline double dual 0.4 recomputed spline 1
    plate3d_short threads "2 threads" double dual 0.4 recomputed wendland 2
    # the first period of mode (2,2) (--tend 0: stop there), frozen geometry as in README's 3D table
    for real in double float; do run plate3d period "first period $real" "$real" 3 eno-a dual 0.4 frozen wendland 1 0 --mode 2,2 --csv-every 0.0002; done

    realtime "dp 0.05" double 0.05 recomputed 0.8
    realtime "dp 0.05 float+frozen" float 0.05 frozen 0.8
    realtime "dp 0.1" double 0.1 recomputed 0.8
    realtime "dp 0.1 float" float 0.1 recomputed 0.8
    realtime "dp 0.1 float+frozen" float 0.1 frozen 0.8
    realtime "dp 0.1 float+frozen no budget" float 0.1 frozen 0
}

# ---- report: markdown tables and SVG plots from knobs.csv ----

# table SCENE METRIC-COLUMN METRIC-TITLE [FILTER]: one row per run of the scene, the default
# first, with the cost and the metric relative to the default's. FILTER is an awk condition.
table() {
    awk -F, -v scene="$1" -v metric="$2" -v title="$3" -v filter="${4:-1}" '
    NR == 1 { for (k = 1; k <= NF; ++k) c[$k] = k; next }
    $c["scene"] != scene { next }
    { row[++n] = $0 }
    $c["knob"] == "default" { base_cpu = $c["cpu_s"]; base_metric = $c[metric] }
    END {
        printf "| knob | setting | particles | sub-steps | CPU [s] | wall [s] | CPU vs default | ns/particle-step | %s | energy drift | status |\n", title
        print "|---|---|---|---|---|---|---|---|---|---|---|"
        for (pass = 0; pass < 2; ++pass)
            for (i = 1; i <= n; ++i) {
                split(row[i], f, ",")
                if ((f[c["knob"]] == "default") != (pass == 0)) continue
                cost = base_cpu > 0 ? sprintf("%.2fx", f[c["cpu_s"]] / base_cpu) : ""
                m = f[c[metric]] == "" ? "-" : f[c[metric]] "%"
                d = f[c["energy_drift_pct"]] == "" ? "-" : f[c["energy_drift_pct"]] "%"
                ns = f[c["ns_cpu"]] == "" ? "-" : f[c["ns_cpu"]]
                # a run that did not stop but whose energy grew tenfold has gone unstable
                status = f[c["energy_drift_pct"]] > 900 ? sprintf("energy x%.0f", 1 + f[c["energy_drift_pct"]] / 100) : f[c["status"]]
                printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", f[c["knob"]], f[c["setting"]], f[c["particles"]],
                       f[c["acoustic_steps"]], f[c["cpu_s"]], f[c["wall_s"]], cost, ns, m, d, status
            }
    }' "$CSV"
}

# float_table: each float run next to the double run of the same scene and settings
float_table() {
    awk -F, '
    NR == 1 { for (k = 1; k <= NF; ++k) c[$k] = k; next }
    { key = $c["scene"] "|" $c["res"] "|" $c["shear"] "|" $c["stepping"] "|" $c["cfl"] "|" $c["geometry"] "|" $c["kernel"] "|" $c["threads"] "|" $c["t_end"]
      if ($c["real"] == "float") { fl[++n] = key; frow[key] = $0 } else if (!(key in drow)) drow[key] = $0 }
    # the accuracy figure of a run: period error, else angular-momentum error, else energy drift
    function pick(r,   f) { split(r, f, ","); return f[c["period_err_pct"]] != "" ? "period_err_pct" : f[c["angmom_err_pct"]] != "" ? "angmom_err_pct" : "energy_drift_pct" }
    function metric(r, col,   f) { split(r, f, ","); return f[c[col]] }
    function cpu(r,   f) { split(r, f, ","); return f[c["cpu_s"]] }
    END {
        print "| scene | settings | metric | double | float | CPU double [s] | CPU float [s] | float/double CPU |"
        print "|---|---|---|---|---|---|---|---|"
        for (i = 1; i <= n; ++i) {
            k = fl[i]
            if (!(k in drow)) continue
            split(frow[k], f, ",")
            col = pick(frow[k])
            what = col == "period_err_pct" ? "period error" : col == "angmom_err_pct" ? "max angular-momentum error" : "energy drift"
            printf "| %s | %s %s, %s, %s, CFL %s, %s | %s | %s%% | %s%% | %s | %s | %.2f |\n", f[c["scene"]], f[c["scene"]] ~ /^(spinning_plate|realtime)$/ ? "dp" : "H/dp",
                   f[c["res"]], f[c["shear"]], f[c["geometry"]], f[c["cfl"]], f[c["t_end"]] == 0 ? "to the first period" : "t = " f[c["t_end"]] " s", what,
                   metric(drow[k], col), metric(frow[k], col), cpu(drow[k]), cpu(frow[k]),
                   (cpu(drow[k]) > 0 ? cpu(frow[k]) / cpu(drow[k]) : 0)
        }
    }' "$CSV"
}

realtime_table() {
    awk -F, '
    NR == 1 { for (k = 1; k <= NF; ++k) c[$k] = k; next }
    $c["scene"] == "realtime" {
        if (!head++) { print "| setting | particles | sub-steps | wall [s] | simulated s per wall s | max angular-momentum error |"; print "|---|---|---|---|---|---|" }
        printf "| %s | %s | %s | %s | %s | %s%% |\n", $c["setting"], $c["particles"], $c["acoustic_steps"], $c["wall_s"], $c["sim_per_wall"], $c["angmom_err_pct"]
    }' "$CSV"
}

report() {
    [ -f "$CSV" ] || { echo "no $CSV: run the sweep first" >&2; exit 1; }
    make -s build/svgplot
    {
        echo "<!-- generated by sh bench/knobs.sh report from knobs.csv; do not edit -->"
        echo
        echo "### 2D plate (H/dp 10, v_f 0.05, ENO-A, t = 0.3 s): first period against thin-plate theory (0.2541 s)"
        echo
        table plate2d period_err_pct "period error"
        echo
        echo "### Spinning plate (dp 0.05, GNO-A, t = 0.5 s): angular-momentum error"
        echo
        table spinning_plate angmom_err_pct "max angular-momentum error"
        echo
        echo "### 3D plate (H/dp 3, mode (2,2), ENO-A, t = 0.002 s; period rows: frozen geometry, to the first period): period error against Kirchhoff theory"
        echo
        table plate3d period_err_pct "period error"
        echo
        echo "### Float against double"
        echo
        float_table
        echo
        echo "### Real-time loop (bench/realtime.c: spinning plate, GNO-A, 60 frames per second, budget 80% of a frame, to t = 0.5 s)"
        echo
        realtime_table
    } > "$OUT/knobs.md"
    ./build/svgplot --csv "$CSV" --where scene=plate2d --x cpu_s --y period_err_pct --abs-y --logx --logy --label setting --pareto \
        --title "2D plate: cost against first-period error (one knob at a time around H/dp 10, ENO-A)" \
        --xlabel "CPU time to t = 0.3 s [s]" --ylabel "|period error| against theory [%]" --out "$OUT/knobs_plate2d.svg"
    ./build/svgplot --csv "$CSV" --where scene=spinning_plate --where stepping=dual --where cfl=0.4 --where geometry=recomputed \
        --where kernel=wendland --where threads=1 --where real=double --x cpu_s --y angmom_err_pct --logx --logy --label setting \
        --group shear --title "Spinning plate: cost against angular-momentum error (dp 0.1, 0.05, 0.033)" \
        --xlabel "CPU time to t = 0.5 s [s]" --ylabel "max angular-momentum error [%]" --out "$OUT/knobs_spinning.svg"
    echo "written $OUT/knobs.md, $OUT/knobs_plate2d.svg, $OUT/knobs_spinning.svg"
}

if [ "${1:-}" != report ]; then
    start=$(date +%s)
    sweep
    echo "sweep took $(($(date +%s) - start)) s"
fi
report
