#!/usr/bin/env bash
# Installs what embray needs to build on Debian/Ubuntu: Embree (libembree-dev: Embree 3 on
# Debian 12, Embree 4 on Debian 13 / Ubuntu 24.04) and libclang for bindgen. Idempotent and
# quiet when everything is already there.
set -euo pipefail

if [ -e /usr/include/embree3/rtcore.h ] || [ -e /usr/include/embree4/rtcore.h ]; then
    if ls /usr/lib/*/libclang*.so* >/dev/null 2>&1 || ls /usr/lib/llvm-*/lib/libclang*.so* >/dev/null 2>&1; then
        exit 0
    fi
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
    SUDO="sudo"
fi
echo "embray setup: installing libembree-dev and libclang-dev with apt-get" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
    libembree-dev libclang-dev >/dev/null
