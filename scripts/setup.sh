#!/usr/bin/env bash
# Installs what embray needs on Debian/Ubuntu: Embree (libembree-dev: Embree 3 on Debian 12,
# Embree 4 on Debian 13 / Ubuntu 24.04), libclang for bindgen, and a TrueType font for the
# chart labels of `embray bench accuracy`. Quiet and quick when everything is there.
set -euo pipefail

have_embree() { [ -e /usr/include/embree3/rtcore.h ] || [ -e /usr/include/embree4/rtcore.h ]; }
have_libclang() { ls /usr/lib/*/libclang*.so* /usr/lib/llvm-*/lib/libclang*.so* >/dev/null 2>&1; }
have_font() { [ -e /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf ]; }

if have_embree && have_libclang && have_font; then
    exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
    SUDO="sudo"
fi
echo "embray setup: installing libembree-dev libclang-dev fonts-dejavu-core with apt-get" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
    libembree-dev libclang-dev fonts-dejavu-core >/dev/null
