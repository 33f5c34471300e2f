#!/usr/bin/env bash
# Makes an Embree 4.4 install prefix on a machine whose packages have only Embree 3 (Debian 12):
#
#   DIR/lib/libembree4-<hash>.so.4   Embree 4.4.0, from PyPI's embreex wheel (manylinux_2_28)
#   DIR/lib/libtbb-<hash>.so.12      the TBB it needs (found through its $ORIGIN rpath)
#   DIR/lib/libembree4.so            -> the above, the name `-lembree4` looks for
#   DIR/include/embree4/*.h          Embree 4 headers vendored by the embree4-sys crate (4.2.0;
#                                    Embree 4.x keeps the ABI within the major version)
#
# and prints DIR. Build and test against it with
#
#   export EMBREE_DIR=$(bash scripts/embree4-runtime.sh)
#   cargo test --features embree4-sys         # bindings from embree4-sys
#   cargo test                                # bindings generated from DIR/include/embree4
#
# build.rs adds DIR/lib to the link path and as an rpath, so the binaries run without
# LD_LIBRARY_PATH. The library keeps its SONAME (libembree4-<hash>.so.4), so it can never be
# mistaken for a system Embree. DIR defaults to ${XDG_CACHE_HOME:-~/.cache}/embray/embree-4.4.0;
# a finished DIR is reused, and a half-made one is never left under that name.
set -euo pipefail

VERSION=4.4.0.post1
DIR=${1:-${XDG_CACHE_HOME:-$HOME/.cache}/embray/embree-4.4.0}
cd "$(dirname "$0")/.."

if [ -e "$DIR/lib/libembree4.so" ] && [ -e "$DIR/include/embree4/rtcore.h" ]; then
    echo "$DIR"
    exit 0
fi

# shellcheck source=scripts/pypi-wheel.sh
source "scripts/pypi-wheel.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
download_wheel embree4-runtime "embreex==$VERSION" manylinux_2_28_x86_64 "$work"
python3 -m zipfile -e "$work"/embreex-*.whl "$work/wheel"

mkdir -p "$work/prefix/lib" "$work/prefix/include"
embree_lib=$(cd "$work/wheel/embreex.libs" && ls libembree4-*.so.4)
cp "$work/wheel/embreex.libs/$embree_lib" "$work/wheel/embreex.libs"/libtbb-*.so.* \
    "$work/prefix/lib/"
ln -s "$embree_lib" "$work/prefix/lib/libembree4.so"

# The headers: embree4-sys's own copy, wherever cargo keeps that crate.
sys_manifest=$(cargo metadata --format-version 1 --features embree4-sys |
    python3 -c 'import json, sys
print(next(p["manifest_path"] for p in json.load(sys.stdin)["packages"] if p["name"] == "embree4-sys"))')
cp -r "$(dirname "$sys_manifest")/lib/embree4" "$work/prefix/include/embree4"

mkdir -p "$(dirname "$DIR")"
rm -rf "$DIR"
mv "$work/prefix" "$DIR"
echo "embree4-runtime: Embree 4 in $DIR" >&2
echo "$DIR"
