#!/usr/bin/env bash
# Embree 3 against Embree 4, side by side: two embray binaries that differ only in the Embree
# they link, on the same scenes, seeds and rays.
#
#   cargo build --release && cp target/release/embray /tmp/embray-e3
#   EMBREE_DIR=$(bash scripts/embree4-runtime.sh) cargo build --release --features embree4-sys \
#       && cp target/release/embray /tmp/embray-e4
#   bash scripts/embree-versions.sh /tmp/embray-e3 /tmp/embray-e4 OUT
#
# Writes into OUT: speed-<binary>-<round>.md (`bench speed`, alternated A B A B so drift hits
# both alike), accuracy-<binary>/ (`bench accuracy`), and per scene the Embree renders of both
# binaries and the obvhs render of the first, their --stats-json counters, and images.txt:
# `embray compare` (PNG) of Embree 3 vs 4 beside Embree 3 vs obvhs (the parity the backends
# keep), and whether the two Embrees' counters are equal.
set -euo pipefail

if [ $# -ne 3 ]; then
    echo "usage: $0 EMBRAY_A EMBRAY_B OUT_DIR" >&2
    exit 2
fi
A=$1
B=$2
OUT=$3
SPEED_ARGS=${SPEED_ARGS:-"--runs 3"}
mkdir -p "$OUT"
cd "$(dirname "$0")/.."

for bin in "$A" "$B"; do
    "$bin" --version
done | tee "$OUT/versions.txt"

for round in 1 2; do
    for bin in "$A" "$B"; do
        name=$(basename "$bin")
        echo "bench speed: $name, round $round" >&2
        # shellcheck disable=SC2086
        "$bin" bench speed $SPEED_ARGS >"$OUT/speed-$name-$round.md"
    done
done

for bin in "$A" "$B"; do
    name=$(basename "$bin")
    echo "bench accuracy: $name" >&2
    "$bin" bench accuracy --runs 1 --out "$OUT/accuracy-$name" >/dev/null
done

: >"$OUT/images.txt"
for scene in scenes/cornell.toml scenes/city_block.toml scenes/instances.toml \
    scenes/moving_boxes.toml scenes/glass.toml; do
    stem=$(basename "$scene" .toml)
    for bin in "$A" "$B"; do
        name=$(basename "$bin")
        "$bin" render "$scene" --backend embree --spp 16 --seed 3 -q \
            -o "$OUT/$stem-$name-embree.exr" --stats-json "$OUT/$stem-$name-embree.json"
    done
    "$A" render "$scene" --backend obvhs --spp 16 --seed 3 -q \
        -o "$OUT/$stem-obvhs.exr" --stats-json "$OUT/$stem-obvhs.json"
    {
        echo "## $stem"
        echo "$(basename "$A") embree vs $(basename "$B") embree:"
        "$A" compare "$OUT/$stem-$(basename "$A")-embree.png" "$OUT/$stem-$(basename "$B")-embree.png"
        echo
        echo "$(basename "$A") embree vs obvhs:"
        "$A" compare "$OUT/$stem-$(basename "$A")-embree.png" "$OUT/$stem-obvhs.png"
        echo
        echo "ray counts (camera, shadow, indirect rays and hits) equal between the two Embrees:"
        python3 -c 'import json, sys
a, b = (json.load(open(p))["stats"] for p in sys.argv[1:])
print("  yes" if a == b else "  NO: %s vs %s" % (a, b))' \
            "$OUT/$stem-$(basename "$A")-embree.json" "$OUT/$stem-$(basename "$B")-embree.json"
    } >>"$OUT/images.txt"
done
cat "$OUT/images.txt"
