#!/usr/bin/env bash
# Makes an Intel Open Image Denoise 2.5.1 install prefix on a machine whose packages have none
# (Debian 12), from PyPI's pyoidn wheel, which carries the official CPU libraries:
#
#   DIR/lib/libOpenImageDenoise.so.2.5.1 (+ .so.2, .so)   the API `-lOpenImageDenoise` links
#   DIR/lib/libOpenImageDenoise_core.so.2.5.1           its core (found through $ORIGIN/../lib)
#   DIR/lib/libOpenImageDenoise_device_cpu.so.2.5.1     the CPU device, loaded at run time
#   DIR/lib/libtbb.so.12                                the TBB the CPU device needs
#
# (the wheel's GPU devices and their runtimes are left out), and prints DIR. Build with
#
#   export OIDN_DIR=$(bash scripts/oidn-runtime.sh)
#   cargo build --release --features denoise
#
# The oidn crate links DIR/lib; build.rs adds DIR/lib as an rpath, so the binaries run
# without LD_LIBRARY_PATH. DIR defaults to ${XDG_CACHE_HOME:-~/.cache}/embray/oidn-2.5.1; a
# finished DIR is reused, and a half-made one is never left under that name.
set -euo pipefail

VERSION=2.5.1.0
DIR=${1:-${XDG_CACHE_HOME:-$HOME/.cache}/embray/oidn-2.5.1}
LIBS="libOpenImageDenoise.so.2.5.1 libOpenImageDenoise_core.so.2.5.1
      libOpenImageDenoise_device_cpu.so.2.5.1 libtbb.so.12"

if [ -e "$DIR/lib/libOpenImageDenoise.so" ] && [ -e "$DIR/lib/libOpenImageDenoise_device_cpu.so.2.5.1" ]; then
    echo "$DIR"
    exit 0
fi

# shellcheck source=scripts/pypi-wheel.sh
source "$(dirname "$0")/pypi-wheel.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
download_wheel oidn-runtime "pyoidn==$VERSION" manylinux2014_x86_64 "$work"   # 88 MB
wheel=$(ls "$work"/pyoidn-*.whl)
mkdir -p "$work/prefix/lib"
# Only the CPU libraries: the wheel's GPU devices and SYCL runtime are most of its size.
python3 - "$wheel" "$work/prefix/lib" $LIBS <<'PY'
import os, sys, zipfile
wheel, dest, names = sys.argv[1], sys.argv[2], sys.argv[3:]
with zipfile.ZipFile(wheel) as z:
    for name in names:
        data = z.read(f"pyoidn/oidn/lib/{name}")
        path = os.path.join(dest, name)
        with open(path, "wb") as f:
            f.write(data)
        os.chmod(path, 0o755)
PY
ln -s libOpenImageDenoise.so.2.5.1 "$work/prefix/lib/libOpenImageDenoise.so.2"
ln -s libOpenImageDenoise.so.2 "$work/prefix/lib/libOpenImageDenoise.so"

mkdir -p "$(dirname "$DIR")"
rm -rf "$DIR"
mv "$work/prefix" "$DIR"
echo "oidn-runtime: Open Image Denoise 2.5.1 in $DIR" >&2
echo "$DIR"
