# Sourced by the scripts that make a library prefix from a PyPI wheel (embree4-runtime.sh,
# oidn-runtime.sh): `download_wheel WHO SPEC PLATFORM DIR` puts the wheel SPEC
# (name==version) for PLATFORM into DIR, installing pip with apt-get first if needed.
# The wheels' libraries do not depend on the Python version; pinning one makes the
# download the same file on every machine.

download_wheel() {
    local who=$1 spec=$2 platform=$3 dir=$4
    if ! python3 -m pip --version >/dev/null 2>&1; then
        local sudo=""
        if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
        echo "$who: installing python3-pip with apt-get (to download the wheel)" >&2
        $sudo apt-get update -qq
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
            python3-pip >/dev/null
    fi
    echo "$who: downloading $spec from PyPI" >&2
    python3 -m pip download --quiet --no-deps --only-binary=:all: \
        --platform "$platform" --python-version 3.11 -d "$dir" "$spec" >&2
}
