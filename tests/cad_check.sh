#!/bin/sh
# cad_check.sh BUILD - the readers against files a CAD tool exports (make cad-check): OpenSCAD
# draws a block with a round hole and a chamfered boss, exports it as ASCII and (where the version
# can) binary STL; admesh computes each file's volume; build/cad_check reads the file, compares its
# volume with admesh's (within 1e-6) and fills it at 20 particles across its smallest feature, the
# 10 mm wall beside the hole (the particles' volume within 2 %). OpenSCAD and admesh come from
# Debian's packages: installed when missing where we are root (apt-get), else the check is
# skipped, saying so.
set -u
build=${1:-build}
if ! command -v openscad >/dev/null 2>&1 || ! command -v admesh >/dev/null 2>&1; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        apt-get install -y -qq --no-install-recommends openscad admesh >/dev/null 2>&1 || apt-get update -qq >/dev/null 2>&1 &&
            apt-get install -y -qq --no-install-recommends openscad admesh >/dev/null 2>&1
    fi
fi
if ! command -v openscad >/dev/null 2>&1 || ! command -v admesh >/dev/null 2>&1; then
    echo "cad-check: OpenSCAD or admesh not available (and not installable here): the check against CAD files is skipped"
    exit 0
fi
dir=$build/cad
mkdir -p "$dir"
cat > "$dir/part.scad" <<'SCAD'
// a 20 x 20 x 10 mm block with a round hole (radius 4), one edge rounded (radius 3)
$fn = 96;
difference() {
    cube([20, 20, 10], center = true);
    cylinder(r = 4, h = 12, center = true);
    translate([7, 0, 2]) difference() {
        translate([0, -11, 0]) cube([4, 22, 4]);
        rotate([90, 0, 0]) cylinder(r = 3, h = 24, center = true);
    }
}
SCAD
status=0
for format in asciistl binstl; do
    out=$dir/part_$format.stl
    if ! QT_QPA_PLATFORM=offscreen openscad --export-format "$format" -o "$out" "$dir/part.scad" >"$dir/openscad_$format.log" 2>&1; then
        if [ "$format" = binstl ]; then echo "cad-check: this OpenSCAD cannot export binary STL: skipped"; continue; fi
        echo "cad-check: openscad failed:"; cat "$dir/openscad_$format.log"; exit 1
    fi
    volume=$(admesh "$out" 2>/dev/null | sed -n 's/.*Volume *: *\([0-9.eE+-]*\).*/\1/p' | head -n 1)
    if [ -z "$volume" ]; then echo "cad-check: admesh printed no volume for $out"; exit 1; fi
    "./$build/cad_check" "$out" "$volume" 6 || status=1
done
exit $status
