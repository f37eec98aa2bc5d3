#!/bin/sh
# Installs the Debian packages sgapi needs to build, test and run, when any is missing.
# Runs apt-get as root, or through sudo otherwise.
set -eu

PACKAGES="gcc make cmake pkg-config libc6-dev libcmocka-dev libstb-dev libcjson-dev libdeflate-dev
    libvulkan-dev mesa-vulkan-drivers glslang-tools
    clang libclang-rt-14-dev valgrind gnuplot-nox python3 ffmpeg
    chromium chromium-driver python3-selenium python3-yaml
    libsdl2-dev xvfb xauth xdotool assimp-testmodels geomview"

missing=""
for p in $PACKAGES; do
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
$SUDO apt-get update
# shellcheck disable=SC2086
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $missing
