#!/bin/sh
# web_check.sh BUILD [WEB_EXTRA] - the demo in a web browser (make test-web): builds the page
# (make web, WEB_EXTRA added to the compiler flags), runs the scripted headless demo there for
# FRAMES (600) frames in headless Chromium (tests/web_run.js), and checks it against the native
# headless demo built by make (BUILD/demo, same scene, same script):
#   - the checksum of the positions, equal: both builds round alike (no FMA contraction: GCC's
#     -std=c99 contracts nothing, the wasm build says -ffp-contract=off and WebAssembly has no FMA);
#   - the picture: the canvas as the browser shows it against the native demo's --png-plain
#     picture of the same frame, by their coarse features (tests/web_compare.js).
# Prints the frame times (median, worst) and the start-up time; FAILS with a broken build, e.g.
# make test-web WEB_EXTRA=-ffast-math. clang, lld, wasi-libc and chromium (and node) come from
# Debian's packages: installed when missing where we are root (apt-get), else the check is
# skipped, saying so.
set -u
build=${1:-build}
extra=${2:-}
frames=${FRAMES:-600}
dir=$build/web_check
tools_missing() {
    ! command -v clang >/dev/null 2>&1 || ! command -v wasm-ld >/dev/null 2>&1 || ! command -v chromium >/dev/null 2>&1 ||
        ! command -v node >/dev/null 2>&1 || [ ! -d /usr/include/wasm32-wasi ] || ! wasm_builtins_present
}
# clang links wasm32 programs against compiler-rt's builtins (libclang_rt.builtins-wasm32.a), a
# package of its own in Debian (libclang-rt-14-dev-wasm32)
wasm_builtins_present() {
    command -v clang >/dev/null 2>&1 && [ -f "$(clang --target=wasm32-wasi -print-libgcc-file-name 2>/dev/null)" ]
}
if tools_missing && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    packages="clang lld wasi-libc libclang-rt-14-dev-wasm32 chromium"
    command -v node >/dev/null 2>&1 || packages="$packages nodejs"
    # shellcheck disable=SC2086 # the package names are words
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $packages >/dev/null 2>&1 ||
        { apt-get update -qq >/dev/null 2>&1 && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $packages >/dev/null 2>&1; }
fi
if tools_missing; then
    echo "test-web: clang with lld, wasi-libc and its wasm32 builtins, chromium or node not available (and not installable here): the browser check is skipped"
    exit 0
fi
mkdir -p "$dir"
rm -f "$build/web/demo.wasm" # built afresh: make does not see a change of WEB_EXTRA
${MAKE:-make} --no-print-directory -s web BUILD="$build" WEB_EXTRA="$extra" >"$dir/make.log" 2>&1 || { echo "test-web: make web failed:"; cat "$dir/make.log"; exit 1; }
bytes=$(cat "$build/web/demo.html" "$build/web/demo.js" "$build/web/demo.wasm" | wc -c)
native=$(OMP_NUM_THREADS=2 "./$build/demo" --headless --frames "$frames" --png-plain --png "$dir/native.png" 2>/dev/null) ||
    { echo "test-web: the native demo failed"; exit 1; }
browser=$(node tests/web_run.js "$build/web" "$frames" "$dir/browser.png") || { echo "test-web: the page did not finish: $browser"; exit 1; }
want=$(echo "$native" | sed -n 's/.*checksum=\([0-9a-f]*\).*/\1/p')
got=$(echo "$browser" | sed -n 's/.*"checksum":"\([0-9a-f]*\)".*/\1/p')
figure() { echo "$browser" | sed -n "s/.*\"$1\":\([0-9.]*\).*/\1/p"; }
echo "test-web: $frames frames in headless Chromium: frame median $(figure median_ms) ms, worst $(figure worst_ms) ms at frame $(figure worst_frame)" \
    "($(figure worst_after_first_30_ms) ms after the first 30; physics and picture);" \
    "start-up $(figure startup_ms) ms to the first frame; page + script + wasm $bytes bytes; load: $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)"
status=0
if [ "$got" = "$want" ]; then
    echo "test-web: checksum $got, the native headless demo's"
else
    echo "test-web: checksum $got, the native headless demo's is $want: FAILED"; status=1
fi
node tests/web_compare.js "$dir/native.png" "$dir/browser.png" || { echo "test-web: the browser's picture ($dir/browser.png) differs from the native one ($dir/native.png): FAILED"; status=1; }
[ $status = 0 ] && echo "test-web: passed (pictures in $dir/)"
exit $status
