#!/bin/bash
# The README's Mitsuba table: every scene of Mitsuba's render suite (and the scenes written
# here, with their references) rendered at the suite's budget of 2·10⁶ samples per image,
# seed 0, three times per backend (median render time), and judged by Mitsuba's rule.
#
#   bash scripts/mitsuba_suite_table.sh [target/release/embray]
#
# Prints one Markdown row per scene: scene, spp, embree s, obvhs s, channels passing, verdict.
set -euo pipefail
cd "$(dirname "$0")/.."
embray=${1:-target/release/embray}
suite=../shared/data/mitsuba/tests/scenes
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

median() { sort -n | sed -n 2p; }

row() { # scene reference-stem label [-D args...]
    local scene=$1 ref=$2 label=$3; shift 3
    local size spp times=()
    size=$("$embray" info "$scene" "$@" 2>/dev/null | grep -o '[0-9]\+ x [0-9]\+\|[0-9]\+x[0-9]\+' | head -1 | tr -d ' ' | tr 'x' ' ')
    read -r w h <<<"$size"
    spp=$((2000000 / (w * h)))
    local verdicts=()
    for backend in embree obvhs; do
        local runs=()
        for _ in 1 2 3; do
            line=$("$embray" render "$scene" "$@" --backend $backend --spp $spp --seed 0 -o "$tmp/out.exr" 2>&1 | grep -o 'render [0-9.]* s' | tail -1)
            runs+=("${line//[^0-9.]/}")
        done
        times+=("$(printf '%s\n' "${runs[@]}" | median)")
        verdicts+=("$("$embray" compare "$tmp/out.exr" "${ref}_ref_rgb.exr" --variance "${ref}_ref_rgb_var.exr" --spp $spp 2>&1 | grep -o '[0-9]* of [0-9]* pixel channels pass ([0-9.]* %' | head -1)")
    done
    local verdict=pass passing=() total=0
    for v in "${verdicts[@]}"; do
        read -r p _ total _ <<<"$v"
        passing+=("$p")
        if (( p * 10000 < total * 9975 )); then verdict=FAIL; fi
    done
    local channels="${passing[0]}"
    [[ "${passing[1]}" != "${passing[0]}" ]] && channels="${passing[0]} (embree), ${passing[1]} (obvhs)"
    local worst=$(( passing[0] < passing[1] ? passing[0] : passing[1] ))
    printf '| %s | %d | %.3f s | %.3f s | %s / %s (%.2f %%) | %s |\n' "$label" $spp "${times[0]}" "${times[1]}" \
        "$channels" "$total" "$(echo "scale=4; 100 * $worst / $total" | bc)" "$verdict"
}

for scene in "$suite"/*/*.xml; do
    stem=$(basename "$scene" .xml)
    ref="$(dirname "$scene")/refs/${stem%_*}"
    row "$scene" "$ref" "\`$(basename "$(dirname "$scene")")/$stem.xml\`"
done
for name in rough_gold shapes emitters thinlens materials textured_emitters; do
    row "tests/data/mitsuba/$name.xml" "tests/data/mitsuba/${name}_48" "\`tests/data/mitsuba/$name.xml\`"
done
for name in cbox cbox-rgb; do
    row "../shared/data/mitsuba/scenes/cbox/$name.xml" "tests/data/mitsuba/${name}_48" \
        "\`scenes/cbox/$name.xml\`, 48²" -D res=48
done
