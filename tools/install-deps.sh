#!/bin/sh
# Installs the Debian packages sgapi needs to build, test and run, when any is missing.
# Runs apt-get as root, or through sudo otherwise.
set -eu

# slurm-wlm and munge: the one-node Slurm cluster the batch-rendering test starts (tests/slurm/).
PACKAGES="gcc make cmake pkg-config libc6-dev libcmocka-dev libstb-dev libcjson-dev libdeflate-dev
    libvulkan-dev mesa-vulkan-drivers glslang-tools glslang-dev g++
    clang libclang-rt-14-dev valgrind gnuplot-nox python3 ffmpeg
    chromium chromium-driver python3-selenium python3-yaml
    libsdl2-dev xvfb xauth xdotool assimp-testmodels geomview
    slurm-wlm munge"
# The AArch64 (NEON) build, tested under emulation by `make test-arm64`: Debian's cross compiler,
# qemu-user, and the arm64 builds of the libraries the core's tests and the renderer link.
# (On an arm64 machine the ordinary build and tests already are the NEON ones.)
ARM64_PACKAGES=""
if [ "$(dpkg --print-architecture)" = amd64 ]; then
    ARM64_PACKAGES="gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user-static
        libcmocka-dev:arm64 libstb-dev:arm64 libcjson-dev:arm64 libdeflate-dev:arm64"
fi

missing=""
for p in $PACKAGES $ARM64_PACKAGES; do
    status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
    case "$status" in
    *"install ok installed"*) ;;
    *) missing="$missing $p" ;;
    esac
done
[ -z "$missing" ] && exit 0

echo "installing:$missing"
if [ "$(id -u)" -eq 0 ]; then
    SUDO=""
elif command -v sudo >/dev/null 2>&1; then
    SUDO="sudo"
else
    echo "error: missing packages ($missing) and not root, and no sudo to install them" >&2
    exit 1
fi
# The :arm64 packages need arm64 among dpkg's architectures (before the package lists are read).
case "$missing" in
*:arm64*)
    if ! dpkg --print-foreign-architectures | grep -qx arm64; then
        $SUDO dpkg --add-architecture arm64
    fi
    ;;
esac
$SUDO apt-get update
# shellcheck disable=SC2086
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $missing
