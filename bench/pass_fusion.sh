#!/bin/sh
# The most that fusing the GNO penalty pass into another neighbour pass can buy
# (bench/VALIDATION.md, "Pass fusion"): the examples built as they are and built with the
# penalty pass skipped (a copy of the header with its call in sps__acoustic_substep disabled:
# no fused loop can cost less than no loop at all), run interleaved by bench/instancing_cost.sh.
# The GNO-A plate's ratio ablated / as-is bounds the fused plate's; the ENO-A plate and the OG
# column collapse run no penalty pass, so theirs should be 1 and show the machine's noise.
#   sh bench/pass_fusion.sh [ROUNDS]
# Defaults: 3 rounds, --threads 1 and 2 (THREADS), the plate to t = 0.3 and the column collapse to
# t = 0.1 (TEND_PLATE2D, TEND_COLUMN). Medians mean something on a quiet
# machine only (see bench/instancing_cost.sh).
set -eu
cd "$(dirname "$0")/.."
rounds=${1:-3}
bins="build/plate2d build/plate3d build/column_collapse2d"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# shellcheck disable=SC2086
make -s $bins
mkdir "$tmp/ablated"
cp -r sphsolid.h Makefile examples "$tmp/ablated/"
call='if (w->bodies\[bi\]\.model\.pass\.penalty) sps__run_groups'
if [ "$(grep -c "$call" sphsolid.h)" -ne 1 ]; then
    echo "pass_fusion.sh: the penalty pass's call in sps__acoustic_substep was not found once; update the pattern" >&2
    exit 1
fi
sed "s/$call/if (0 \&\& w->bodies[bi].model.pass.penalty) sps__run_groups/" sphsolid.h > "$tmp/ablated/sphsolid.h"
# shellcheck disable=SC2086
(cd "$tmp/ablated" && make -s $bins)
echo "old = as built, new = without the penalty pass"
TEND_PLATE2D=${TEND_PLATE2D:-0.3} TEND_COLUMN=${TEND_COLUMN:-0.1} sh bench/instancing_cost.sh build "$tmp/ablated/build" "$rounds"
