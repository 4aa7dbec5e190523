#!/bin/sh
# scene_census.sh - per example, the calls of the library (sps_*) against the calls of the harness
# (the functions and function-like macros that examples/common.h and examples/render.h define:
# options, output, RESULT lines, pictures, fits) and of the shared scenes (examples/scenes/*.h,
# shown apart: the set-up they hold is library calls the example does not show). An example
# reads as a scene when the library's calls outnumber the harness's.
#   sh bench/scene_census.sh [-v] [examples/NAME.c ...]  (-v lists each example's harness calls)
# By default every examples/*.c but impl.c (the implementation's translation unit) and demo.c (the
# terminal renderer and keyboard loop around the play of scenes/demo_play.h, which the web page
# shares); name them to count them too.
# Comments and string literals are left out (gcc -fpreprocessed strips the comments; the macros
# are not expanded, so a macro counts as one call). Prints the table, then the examples where
# the harness's calls are as many or more.
set -e
cd "$(dirname "$0")/.."
CC=${CC:-gcc}
tmp=${TMPDIR:-/tmp}/scene_census.$$
mkdir -p "$tmp"
trap 'rm -rf "$tmp"' EXIT INT TERM
# the source without comments and strings (one call per match: NAME followed by "(")
clean() { $CC -fpreprocessed -dD -E -P "$1" 2>/dev/null | sed 's/"\([^"\\]\|\\.\)*"/""/g; s/'"'"'\([^'"'"'\\]\|\\.\)'"'"'/0/g'; }
# the names a header defines: functions (a line starting a definition) and function-like macros
names() {
    clean "$1" | sed -n 's/^#define \([A-Za-z_][A-Za-z0-9_]*\)(.*/\1/p; s/^\(static \|EX_UNUSED \|SCENE_UNUSED \|RENDER_UNUSED \|inline \)\{1,\}[A-Za-z_][A-Za-z0-9_ *]*[ *]\([A-Za-z_][A-Za-z0-9_]*\)(.*/\2/p' | sort -u
}
{ names examples/common.h; names examples/render.h; } | sort -u > "$tmp/harness"
for h in examples/scenes/*.h; do names "$h"; done | sort -u | grep -v -x -F -f "$tmp/harness" > "$tmp/scene" || true
# the names called in FILE, one a line (a match starts at an identifier's first character: grep
# takes the leftmost match)
calls() { grep -o -E '[A-Za-z_][A-Za-z0-9_]*[[:space:]]*\(' "$1" | sed 's/[[:space:](]*$//'; }
verbose=0
if [ "$1" = -v ]; then verbose=1; shift; fi
if [ $# -eq 0 ]; then set -- $(ls examples/*.c | grep -v -x -e 'examples/impl.c' -e 'examples/demo.c'); fi
printf '%-22s %8s %8s %8s\n' example library harness scenes
leading=0; total=0; list=
for f in "$@"; do
    clean "$f" > "$tmp/src"
    calls "$tmp/src" > "$tmp/calls"
    lib=$(grep -c '^sps_[a-z0-9_]*$' "$tmp/calls" || true)
    har=$(grep -c -x -F -f "$tmp/harness" "$tmp/calls" || true)
    sce=$(grep -c -x -F -f "$tmp/scene" "$tmp/calls" || true)
    name=$(basename "$f" .c)
    printf '%-22s %8d %8d %8d\n' "$name" "$lib" "$har" "$sce"
    if [ $verbose = 1 ]; then
        grep -x -F -f "$tmp/harness" "$tmp/calls" | sort | uniq -c | awk '{printf "    %s x%s\n", $2, $1}'
    fi
    total=$((total + 1))
    if [ "$har" -ge "$lib" ]; then leading=$((leading + 1)); list="$list $name"; fi
done
echo "examples where the harness's calls are as many as the library's or more: $leading of $total${list:+ (}${list# }${list:+)}"
