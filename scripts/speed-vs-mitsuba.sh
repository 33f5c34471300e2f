#!/usr/bin/env bash
# The three speed figures issue 35 is judged by, measured side by side on this machine:
#
#   time per sample     embray's render time / Mitsuba 3's (llvm_ad_rgb), Cornell box 256²,
#                       at 64 and 256 spp (the peers harness: one run each, strictly one
#                       renderer after the other, render time without loading)
#   time to equal error (MSE × seconds) / Mitsuba's, the median over those spp
#   Embree's share      of a 64-spp render's `perf record` profile, by library
#
#   bash scripts/speed-vs-mitsuba.sh [EMBRAY_BINARY]     (default: a release build of this tree)
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

if grep -qw avx512f /proc/cpuinfo; then isa=AVX-512; elif grep -qw avx2 /proc/cpuinfo; then isa=AVX2; else isa="neither AVX2 nor AVX-512"; fi
echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) cores, $isa"
echo "embray: $("$embray" --version | head -1)"

PEERS_DIR=$peers_dir "$python" "$harness/equal_error.py" "$embray" --scene cornell --spps 64,256 \
    --only embray,mitsuba --out "$work/equal_error" > "$work/harness.log" 2>&1 ||
    { cat "$work/harness.log" >&2; echo "the peers harness failed (its log above)" >&2; exit 1; }

"$python" - "$work/equal_error/equal_error.jsonl" <<'PY'
import json, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
by = {(r["renderer"], r["spp"]): r for r in rows}
print("| spp | embray s | Mitsuba s | per sample, embray / Mitsuba | MSE × s, embray / Mitsuba |")
print("|---:|---:|---:|---:|---:|")
for spp in sorted({r["spp"] for r in rows}):
    e, m = by[("embray", spp)], by[("mitsuba", spp)]
    print(f"| {spp} | {e['render_s']:.2f} | {m['render_s']:.2f} | "
          f"{e['render_s'] / m['render_s']:.2f}× | {e['work'] / m['work']:.2f}× |")
PY
# The harness's own summary line (its median rule, not a copy of it).
grep "time to equal error" "$work/harness.log"

perf record -q -e cpu-clock -F 2000 -o "$work/perf.data" \
    "$embray" render "$harness/embray/cornell.toml" --spp 64 -o "$work/perf.exr" -q 2>/dev/null
perf report -i "$work/perf.data" --no-children --sort dso -g none 2>/dev/null |
    awk '/libembree/ { share += $1 } END { printf "Embree share of a 64-spp render (perf, by library): %.1f %%\n", share }'
