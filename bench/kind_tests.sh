#!/bin/sh
# kind_tests.sh - which functions of sphsolid.h ask which material kind a body is, outside that
# kind's own chapters (>>material: ...) and the generic chapter (>>generic): the library
# dispatches on the kind in one place, and this counts the exceptions. A kind test is its enum value (SPS_MATERIAL_x,
# an assignment "kind = SPS_MATERIAL_x;" excepted) or its yield surface (SPS__YIELD_x). Listed
# after them, not counted: the functions that read a property of the material's row
# (kinematic, mirrored, pressure_of_density, riemann_density, shear), which a new kind sets in
# its own row. Usage: bench/kind_tests.sh [sphsolid.h]   (a top-level definition is a function
# or a table: from a line starting with a name and "(" or "[] = {" to its closing brace)
header=${1:-sphsolid.h}
awk '
BEGIN {
    n = split("elastic|SPS_MATERIAL_ELASTIC|>>material: linear elastic;" \
              "rigid|SPS_MATERIAL_RIGID|>>material: rigid;" \
              "J2|SPS_MATERIAL_J2|SPS__YIELD_VON_MISES|>>material: J2;" \
              "fluid|SPS_MATERIAL_FLUID|>>material: weakly compressible fluid;" \
              "Saint Venant-Kirchhoff|SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF|>>material: Saint Venant-Kirchhoff;" \
              "Neo-Hookean|SPS_MATERIAL_NEO_HOOKEAN|>>material: Neo-Hookean;" \
              "Drucker-Prager|SPS_MATERIAL_DRUCKER_PRAGER|SPS__YIELD_DRUCKER_PRAGER|>>material: Drucker-Prager;" \
              "(property) kinematic|[.>]kinematic|>>generic;(property) mirrored|[.>]mirrored|>>generic;" \
              "(property) pressure_of_density|[.>]pressure_of_density|>>generic;" \
              "(property) riemann_density|[.>]riemann_density|>>generic;(property) shear|material->shear|>>generic", rows, ";")
    for (r = 1; r <= n; ++r) {
        m = split(rows[r], f, "|")
        kind[r] = f[1]; owner[r] = f[m]; pattern[r] = f[2]
        for (k = 3; k < m; ++k) pattern[r] = pattern[r] "|" f[k]
    }
}
/^\/\* >>/ { chapter = $0; next }
{   line = $0; gsub(/"([^"\\]|\\.)*"/, "\"\"", line); gsub(/\/\*([^*]|\*[^\/])*\*\//, "", line)
    sub(/\/\*.*/, "", line); if (line ~ /^[ \t]*\*/) line = ""
    gsub(/kind = SPS_MATERIAL_[A-Z_]*;/, "", line) }
name == "" && /^[A-Za-z_]/ && !/^(typedef|struct|enum|union)/ && /\(|\[\] = \{/ {
    name = line; sub(/[ \t]*\(.*/, "", name); sub(/\[\].*/, "", name); sub(/.*[ *]/, "", name); body = ""; depth = 0; opened = 0
}
name != "" {
    body = body "\n" line
    t = line; opens = gsub(/\{/, "", t); t = line; closes = gsub(/\}/, "", t)
    depth += opens - closes; if (opens) opened = 1
    if (!opened && line ~ /;[ \t]*$/) { name = ""; next }
    if (opened && depth == 0) {
        for (r = 1; r <= n; ++r)
            if (body ~ pattern[r] && index(chapter, owner[r]) == 0 && index(chapter, ">>generic") == 0) {
                c = chapter; sub(/^\/\* /, "", c); sub(/ \(.*/, "", c); sub(/ \*\/.*/, "", c)
                hits[r] = hits[r] "    " name " (" c ")\n"; count[r]++
            }
        name = ""
    }
}
END {
    for (r = 1; r <= n; ++r) {
        if (kind[r] ~ /^\(property\)/ && !said) { print "not counted, the properties of the row read outside >>generic:"; said = 1 }
        printf "%s: %d\n%s", kind[r], count[r] + 0, hits[r]
    }
}
' "$header"
