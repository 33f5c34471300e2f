#!/usr/bin/env bash
# The three speed figures issue 35 is judged by, measured side by side on this machine:
#
#   time per sample     embray's render time / Mitsuba 3's (llvm_ad_rgb), Cornell box 256²,
#                       at 64 and 256 spp (the peers harness: strictly one renderer after the
#                       other, render time without loading), in ROUNDS rounds (default 3):
#                       the median of the rounds' ratios
#   time to equal error (MSE × seconds) / Mitsuba's: the harness's median over those spp,
#                       then the median over the rounds
#   Embree's share      of a 64-spp render's `perf record` profile, by library (and, beside
#                       it, Mitsuba's profile of the same render: Embree and its JIT kernel)
#   (and, beside them, embray's threads' time by phase of a 64-spp render: `--time-phases`)
#
#   [ROUNDS=3] [EMBRAY_ARGS=...] [RR_DEPTH=...] bash scripts/speed-vs-mitsuba.sh [EMBRAY_BINARY]
#
# Like for like: the harness renders Mitsuba with its `rr_depth` default of 5 (Russian
# roulette from the fifth surface interaction on), and embray's copy of the scene sets none,
# so embray would take its own default of 4, which traces 10 % fewer rays a sample. The
# script renders a copy of the harness whose embray scene sets Mitsuba's `rr_depth` (read
# from the harness); RR_DEPTH=4 measures embray's default instead.
#
# (default binary: a release build). EMBRAY_ARGS are added to every embray render, e.g.
# EMBRAY_ARGS="--intersection fast --build-quality high" for Mitsuba 3's own Embree settings
# (RTC_SCENE_FLAG_NONE, RTC_BUILD_QUALITY_HIGH) instead of embray's robust default.
#
# Needs the peers' Python environment (`SKIP_BPY=1 bash ../shared/peers/setup_peers.sh`,
# found through $PEERS_DIR, default /tmp/peers) and `perf`. Prints the CPU's widest vector
# unit too: Mitsuba's kernels are 16 lanes wide on AVX-512 and 8 on AVX2, so the ratios
# depend on it. Timings on a shared machine drift 10-20 %: compare runs made together.
set -euo pipefail
cd "$(dirname "$0")/.."

peers_dir=${PEERS_DIR:-/tmp/peers}
harness=${PEERS_HARNESS:-../shared/peers}
python="$peers_dir/venv/bin/python"
[ -x "$python" ] || { echo "no peers environment at $peers_dir (run $harness/setup_peers.sh)" >&2; exit 1; }
command -v perf >/dev/null || { echo "perf is not installed" >&2; exit 1; }

if [ $# -ge 1 ]; then
    embray=$1
else
    cargo build --release --quiet
    embray=target/release/embray
fi
[ -x "$embray" ] || { echo "$embray: not an executable" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Mitsuba's roulette start, as the harness renders it, given to embray's scene in a copy of
# the harness (its scripts find their files next to themselves).
mitsuba_rr=$(sed -n 's/.*"--rr-depth", type=int, default=\([0-9]*\).*/\1/p' "$harness/mitsuba_render.py")
[ -n "$mitsuba_rr" ] || { echo "no --rr-depth default found in $harness/mitsuba_render.py" >&2; exit 1; }
rr_depth=${RR_DEPTH:-$mitsuba_rr}
[[ $rr_depth =~ ^[1-9][0-9]*$ ]] || { echo "RR_DEPTH must be a whole number of at least 1" >&2; exit 1; }
# The shared harness may be read-only: the copy is made writable.
cp -r --no-preserve=mode "$harness" "$work/harness"
harness=$work/harness
scene=$harness/embray/cornell.toml
grep -q '^rr_depth' "$scene" && { echo "$scene already sets rr_depth" >&2; exit 1; }
sed -i "s/^\[render\]\$/[render]\nrr_depth = $rr_depth/" "$scene"
grep -q "^rr_depth = $rr_depth\$" "$scene" || { echo "$scene: no [render] table to set rr_depth in" >&2; exit 1; }

if grep -qw avx512f /proc/cpuinfo; then isa=AVX-512; elif grep -qw avx2 /proc/cpuinfo; then isa=AVX2; else isa="neither AVX2 nor AVX-512"; fi
echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) cores, $isa"
echo "embray: $("$embray" --version | head -1)${EMBRAY_ARGS:+, with $EMBRAY_ARGS}"
echo "Russian roulette from interaction $rr_depth for embray, $mitsuba_rr for Mitsuba (its default)"
read -ra embray_args <<< "${EMBRAY_ARGS:-}"

rounds=${ROUNDS:-3}
for round in $(seq "$rounds"); do
    PEERS_DIR=$peers_dir "$python" "$harness/equal_error.py" "$embray" --scene cornell \
        --spps 64,256 --only embray,mitsuba "--embray-args=${EMBRAY_ARGS:-}" --out "$work/round$round" > "$work/harness$round.log" 2>&1 ||
        { cat "$work/harness$round.log" >&2; echo "the peers harness failed (its log above)" >&2; exit 1; }
done

# One run of each renderer moves by 10-20 % on a shared machine (Mitsuba's own 64-spp time
# has ranged over 2.4-3.2 s here): each round pairs the two, and the table gives medians.
"$python" - "$work" "$rounds" <<'PY'
import json, re, statistics, sys
work, rounds = sys.argv[1], int(sys.argv[2])
runs = []
for r in range(1, rounds + 1):
    rows = [json.loads(line) for line in open(f"{work}/round{r}/equal_error.jsonl")]
    runs.append({(row["renderer"], row["spp"]): row for row in rows})
med = statistics.median
print(f"rounds: {rounds}; each cell is the median over the rounds (range in brackets)")
print("| spp | embray s | Mitsuba s | per sample, embray / Mitsuba | MSE × s, embray / Mitsuba |")
print("|---:|---:|---:|---:|---:|")
for spp in sorted({spp for run in runs for (_, spp) in run}):
    e = [run[("embray", spp)] for run in runs]
    m = [run[("mitsuba", spp)] for run in runs]
    ratio = [a["render_s"] / b["render_s"] for a, b in zip(e, m)]
    work_ratio = [a["work"] / b["work"] for a, b in zip(e, m)]
    print(f"| {spp} | {med(a['render_s'] for a in e):.2f} | {med(b['render_s'] for b in m):.2f} | "
          f"{med(ratio):.2f}× ({min(ratio):.2f}-{max(ratio):.2f}) | {med(work_ratio):.2f}× |")
# The harness's own summary (its median rule over spp, not a copy of it), per round.
equal = []
for r in range(1, rounds + 1):
    line = next(l for l in open(f"{work}/harness{r}.log") if "time to equal error" in l)
    equal.append(float(re.search(r"([0-9.]+)x", line).group(1)))
print(f"time to equal error, embray / mitsuba: {med(equal):.2f}x (median over the rounds of the "
      f"harness's median over spp; rounds: {', '.join(f'{x:.2f}' for x in equal)})")
PY

# profile FILE COMMAND...: a `perf record` of the command into FILE.
profile() {
    local data=$1
    shift
    perf record -q -e cpu-clock -F 2000 -o "$data" "$@" > /dev/null 2>&1
}
# share FILE PATTERN: the per cent of profile FILE in the libraries matching the awk regex.
share() {
    perf report -i "$1" --no-children --sort dso -g none 2>/dev/null |
        awk -v pattern="$2" '$0 ~ pattern { share += $1 } END { printf "%.1f", share }'
}

profile "$work/perf.data" "$embray" render "$scene" --spp 64 -o "$work/perf.exr" -q "${embray_args[@]}"
echo "Embree share of a 64-spp render (perf, by library): $(share "$work/perf.data" libembree) %"

# Mitsuba's split of the same render, as the harness runs it (two renders in one process,
# its default rr_depth): Embree's share and its JIT-compiled kernel's. Beside embray's
# share it says whose Embree work or whose shading a gap is in (the README's "where each
# renderer's time per sample goes").
profile "$work/perf-mitsuba.data" env PEERS_DIR="$peers_dir" "$python" \
    "$harness/mitsuba_render.py" "$harness/scenes/cornell/scene.json" --variant llvm_ad_rgb \
    --spp 64 --max-depth 8 --repeat 2 --out "$work/perf-mitsuba"
echo "Mitsuba's profile of the same render: Embree $(share "$work/perf-mitsuba.data" libembree) %," \
    "its JIT-compiled kernel $(share "$work/perf-mitsuba.data" '\\[JIT\\]') %"

# Where embray's own time goes, by phase of the batched path tracer (`--time-phases`).
echo "embray's time by phase (summed over its threads), 64 spp:"
"$embray" render "$scene" --spp 64 -o "$work/phases.exr" -q --time-phases "${embray_args[@]}" |
    sed -n '/^phase /,$p'
