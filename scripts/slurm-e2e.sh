#!/usr/bin/env bash
# slurm-e2e.sh — embray on a real (local, one-node) Slurm cluster, as CI runs it after
# `cargo test`:
#   1. `embray slurm` renders the bundled Cornell box as 4 array tasks; the merged EXR must
#      equal `embray render`'s byte for byte;
#   2. the fault: one array task is cancelled while it runs; the merge must not run,
#      `embray slurm status` must name the missing part, `embray slurm resume` must complete
#      it, and the result must still be byte-identical.
# Every step is printed (this is the log quoted in the closing note). Exits non-zero on any
# failure. Usage: bash scripts/slurm-e2e.sh [EMBRAY_BINARY]   (default: target/debug/embray)
set -euo pipefail
cd "$(dirname "$0")/.."
EMBRAY="$(realpath "${1:-target/debug/embray}")"
SCENE="$(realpath scenes/cornell.toml)"
WORK="$(mktemp -d /tmp/embray-slurm-e2e.XXXXXX)"
trap 'rm -rf "$WORK"' EXIT
say() { echo "+ $*" >&2; }
fail() { echo "slurm-e2e: FAILED: $*" >&2; exit 1; }

bash scripts/slurm-local.sh start

# 1. Four tasks, tiles split, compared with the whole render.
say "embray render (whole) at 16 spp"
"$EMBRAY" render "$SCENE" --spp 16 --quiet -o "$WORK/whole16.exr"
say "embray slurm --parts 4 (tiles) at 16 spp"
"$EMBRAY" slurm "$SCENE" --parts 4 --out "$WORK/run1" -- --spp 16
cmp "$WORK/whole16.exr" "$WORK/run1/render.exr" || fail "the merged EXR differs from the whole render"
say "run 1: merged EXR is byte-identical to the whole render"

# 2. The fault: samples split, heavy enough that a task runs for several seconds.
SPP=256
say "embray render (whole) at $SPP spp"
"$EMBRAY" render "$SCENE" --spp $SPP --quiet -o "$WORK/whole.exr"
say "embray slurm --parts 4 --split samples --no-wait at $SPP spp"
"$EMBRAY" slurm "$SCENE" --parts 4 --split samples --out "$WORK/run2" --no-wait -- --spp $SPP
ARRAY="$(sed -n 's/.*"array_job": "\([0-9]*\)".*/\1/p' "$WORK/run2/job.json" | head -n 1)"
MERGE="$(sed -n 's/.*"merge_job": "\([0-9]*\)".*/\1/p' "$WORK/run2/job.json" | head -n 1)"
[[ -n $ARRAY && -n $MERGE ]] || fail "no job ids in job.json"
for _ in $(seq 1 600); do
    state="$(squeue -h -r -j "${ARRAY}_1" -o %T 2>/dev/null || true)"
    [[ $state == RUNNING ]] && break
    sleep 0.1
done
[[ $state == RUNNING ]] || fail "task ${ARRAY}_1 never ran (state '$state')"
sleep 1
say "scancel ${ARRAY}_1 (task 1 is RUNNING)"
scancel "${ARRAY}_1"
# Wait for the rest of the array to end.
for _ in $(seq 1 600); do
    live="$(squeue -h -r -j "$ARRAY" -t PENDING,RUNNING,COMPLETING -o %i 2>/dev/null | wc -l)"
    [[ $live == 0 ]] && break
    sleep 0.5
done
sleep 2
say "squeue -t all -j $ARRAY,$MERGE"
squeue -t all -r -j "$ARRAY,$MERGE" -o '%i %T %r' >&2
[[ ! -e $WORK/run2/parts/part-1-of-4.exr ]] || fail "the cancelled part left a file"
[[ ! -e $WORK/run2/render.exr ]] || fail "the merge ran without part 1"
leftovers="$(find "$WORK/run2/parts" -mindepth 1 ! -name 'part-*-of-4.exr')"
[[ -z $leftovers ]] || fail "files left in parts/: $leftovers"
say "embray slurm status"
status="$("$EMBRAY" slurm status "$WORK/run2")"
echo "$status" >&2
grep -q "^part 1/4  missing" <<<"$status" || fail "status does not name part 1/4 as missing"
grep -q "missing: 1/4\." <<<"$status" || fail "status does not list 1/4 as missing"
say "embray slurm resume"
"$EMBRAY" slurm resume "$WORK/run2"
say "embray slurm status (after resume)"
"$EMBRAY" slurm status "$WORK/run2" >&2
cmp "$WORK/whole.exr" "$WORK/run2/render.exr" || fail "the resumed merge differs from the whole render"
say "run 2: after cancel + resume, merged EXR is byte-identical to the whole render"
echo "slurm-e2e: 2 passed, 0 failed"
