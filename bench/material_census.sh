#!/bin/sh
# The material census (issue 48): for each material kind, the functions, tables and macros of
# sphsolid.h outside its own chapters (">>material: <its title>", continued or not) and
# ">>generic" whose code (comments and strings left out) names the kind or one of its own
# identifiers: its enum value, its parameter sub-struct (material.j2, .fluid, .granular), its
# per-body state and its hooks' prefix. Each such unit is a place where the kind's physics
# lives outside its module; the goal is 0 for every kind.
#   sh bench/material_census.sh [sphsolid.h] [-v]   (-v: list the units, not only count them)
# POSIX sh and awk only.
header=sphsolid.h
verbose=0
for a in "$@"; do
    case $a in
    -v) verbose=1 ;;
    *) header=$a ;;
    esac
done
[ -r "$header" ] || { echo "material_census: cannot read $header" >&2; exit 1; }

# kind | the chapter title its chapters start with | the identifiers (an ERE on code) that are its own
kinds='elastic|material: linear elastic|SPS_MATERIAL_ELASTIC\>|sps__elastic_
rigid|material: rigid (wall bodies)|SPS_MATERIAL_RIGID\>|sps__rigid_(energy|model|kind|material)|sps__damped_wall|sps__moving_wall_particles
free rigid|material: free rigid bodies|SPS_MATERIAL_RIGID_DYNAMIC|sps__free_rigid
J2|material: J2 plasticity|SPS_MATERIAL_J2|SPS__LAW_J2|[.>]j2\.|sps__j2_|sps__tl_j2|SPS__YIELD_VON_MISES|sps__radial_return
fluid|material: weakly compressible fluid|SPS_MATERIAL_FLUID\>|[.>]fluid\.(sound_speed|dissipation)|SPS_FLUID_DISSIPATION_|sps__fluid_(constants|check|energy|material|model|rest|fills|warnings)|sps__newton_dt|sps__inviscid_
Drucker-Prager|material: Drucker-Prager|SPS_MATERIAL_DRUCKER_PRAGER|[.>]granular\.|sps__granular_|sps__drucker_prager|SPS_CONE_|sps__yield_cone|SPS__YIELD_DRUCKER_PRAGER|->cone\>|[.>]geostatic\>|diffusion_rate
Saint Venant-Kirchhoff|material: Saint Venant-Kirchhoff|SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF|SPS__LAW_SAINT_VENANT_KIRCHHOFF|sps__saint_venant_kirchhoff|sps__svk_
Neo-Hookean|material: Neo-Hookean|SPS_MATERIAL_NEO_HOOKEAN|SPS__LAW_NEO_HOOKEAN|sps__neo_hookean'

total=0
echo "kind                     units outside its chapters and >>generic"
printf '%s\n' "$kinds" | while IFS='|' read -r kind title pattern_rest; do
    pattern=$(printf '%s' "$pattern_rest" | sed 's/^//')
    awk -v kind="$kind" -v title="$title" -v pattern="$pattern" -v verbose="$verbose" '
    function flush_unit() {
        if (unit != "" && unit_hit && !own(unit_chapter)) { count++; listed = listed "\n    " unit "  (>>" unit_chapter ")" }
        unit = ""; unit_hit = 0
    }
    function own(chapter) { return index(chapter, title) == 1 || index(chapter, "generic") == 1 }
    BEGIN { depth = 0; in_comment = 0; in_macro = 0; buffer = ""; chapter = "" }
    {
        line = $0
        if (line ~ /^\/\* >>/) { c = line; sub(/^\/\* >>/, "", c); sub(/[ \t]*\*\/.*$/, "", c); chapter = c }
        # code only: comments (also across lines) and strings out
        code = ""
        while (length(line) > 0) {
            if (in_comment) {
                p = index(line, "*/")
                if (p == 0) { line = ""; break }
                line = substr(line, p + 2); in_comment = 0
            } else {
                p = index(line, "/*")
                if (p == 0) { code = code line; line = ""; break }
                code = code substr(line, 1, p - 1); line = substr(line, p + 2); in_comment = 1
            }
        }
        gsub(/"([^"\\]|\\.)*"/, "\"\"", code)
        gsub(/\x27([^\x27\\]|\\.)*\x27/, "0", code)
        if (in_macro) {
            if (code ~ pattern) unit_hit = 1
            if (code !~ /\\[ \t]*$/) { in_macro = 0; flush_unit() }
            next
        }
        if (depth == 0 && code ~ /^#[ \t]*define[ \t]+[A-Za-z_]/) {
            flush_unit()
            n = code; sub(/^#[ \t]*define[ \t]+/, "", n); match(n, /^[A-Za-z_][A-Za-z0-9_]*/)
            unit = substr(n, 1, RLENGTH); unit_chapter = chapter; unit_hit = code ~ pattern
            if (code ~ /\\[ \t]*$/) in_macro = 1
            else flush_unit()
            next
        }
        if (code ~ /^[ \t]*#/) next
        for (k = 1; k <= length(code); k++) {
            ch = substr(code, k, 1)
            if (depth == 0) {
                if (ch == "{") {
                    name = ""
                    if (buffer !~ /(typedef|^[ \t]*(struct|enum|union)[ \t])/ && buffer !~ /extern[ \t]+"C"/ && buffer !~ /""/) {
                        b = buffer
                        if (match(b, /[A-Za-z_][A-Za-z0-9_]*[ \t]*\(/)) { name = substr(b, RSTART, RLENGTH); sub(/[ \t]*\($/, "", name) }
                        else if (match(b, /[A-Za-z_][A-Za-z0-9_]*[ \t]*(\[[^]]*\])?[ \t]*=[ \t]*$/)) { name = substr(b, RSTART, RLENGTH); sub(/[ \t]*(\[[^]]*\])?[ \t]*=[ \t]*$/, "", name) }
                    }
                    flush_unit()
                    unit = name; unit_chapter = chapter; unit_hit = buffer ~ pattern
                    buffer = ""; depth = 1
                } else if (ch == ";") { buffer = "" }
                else buffer = buffer ch
            } else {
                if (ch == "{") depth++
                else if (ch == "}") { depth--; if (depth == 0) { unit_text_end = 1 } }
            }
        }
        if (unit != "" && code ~ pattern) unit_hit = 1
        if (depth == 0 && unit != "") flush_unit()
        if (depth == 0) buffer = buffer " "
    }
    END {
        printf "%-24s %d\n", kind, count
        if (verbose && count) print substr(listed, 2)
    }' "$header"
done
