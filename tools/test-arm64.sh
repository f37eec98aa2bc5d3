#!/bin/sh
# Cross-builds sgapi for 64-bit ARM (AArch64) with Debian's cross compiler and runs it under
# qemu-user: the unit tests (the NEON shading functions against the scalar reference among them),
# then every scene file of scenes/, the hard cases of scenes/hard/ and the gapi-task suite (when it
# sits beside the checkout), rendered on AArch64 with the scalar code (one thread) and with NEON
# (three threads), every image compared byte for byte with the x86-64 build's. Speed is not
# measured: emulation says nothing about it.
#
#   tools/test-arm64.sh X86_BUILD_DIR ARM_BUILD_DIR [JOBS]
#   tools/test-arm64.sh --available   exit status 0 when the cross compiler and qemu are installed
set -eu

qemu=$(command -v qemu-aarch64-static || command -v qemu-aarch64 || true)
if [ "${1:-}" = "--available" ]; then
    [ -n "$qemu" ] && command -v aarch64-linux-gnu-gcc >/dev/null 2>&1 &&
        [ -f /usr/lib/aarch64-linux-gnu/pkgconfig/cmocka.pc ]
    exit
fi
x86=${1:?usage: tools/test-arm64.sh X86_BUILD_DIR ARM_BUILD_DIR [JOBS]}
arm=${2:?usage: tools/test-arm64.sh X86_BUILD_DIR ARM_BUILD_DIR [JOBS]}
jobs=${3:-2}
src=$(cd "$(dirname "$0")/.." && pwd)
[ -n "$qemu" ] || { echo "test-arm64: no qemu-aarch64-static (tools/install-deps.sh)" >&2; exit 1; }
start=$(date +%s)

# The reference renderer needs Vulkan, which the arm64 build does not link.
cmake -S "$src" -B "$arm" -DCMAKE_TOOLCHAIN_FILE="$src/cmake/aarch64-linux-gnu.cmake" \
    -DCMAKE_BUILD_TYPE=Release -DSGAPI_BUILD_REFERENCE=OFF >/dev/null
cmake --build "$arm" -j "$jobs"

# The unit tests of the stages and the API; ctest runs them through the emulator (the toolchain
# file's CMAKE_CROSSCOMPILING_EMULATOR).
(cd "$arm" && ctest --output-on-failure --no-tests=error -j "$jobs" \
    -R '^(test_.*|api|robust|util|scene_loader|turntable)$')

# Every image of AArch64's scalar and NEON code against the x86-64 one.
work=$arm/arm64_check
rm -rf "$work"
# PNG level 0 throughout: the pixels are what is compared, and compressing them under emulation
# took a sixth of the renders (85 s against 75 s for the stage, its build done).
render_all() { # OUT_DIR COMMAND...: renders every scene file with the command
    out=$1
    shift
    set -- "$@" --png-level 0
    for f in "$src"/scenes/*.json; do
        [ "${f##*/}" = scale.json ] && continue # millions of triangles a scene: for sgapi-bench
        "$@" "$f" -o "$out/$(basename "$f" .json)" >/dev/null
    done
    for f in "$src"/scenes/hard/*.json; do
        case $f in *.reference.json) continue ;; esac # lavapipe's twins of some hard cases
        "$@" "$f" -o "$out/hard" >/dev/null
    done
    gapi=$src/../shared/gapi-task/scenes.json
    if [ -f "$gapi" ]; then "$@" "$gapi" -o "$out/gapi-task" >/dev/null; fi
}
render_all "$work/x86" "$x86/apps/sgapi-render"
# The scalar run takes one core: the NEON run beside it takes the other.
render_all "$work/scalar" "$qemu" "$arm/apps/sgapi-render" --simd scalar --threads 1 &
scalar_pid=$!
render_all "$work/neon" "$qemu" "$arm/apps/sgapi-render" --simd neon --threads 3 &
neon_pid=$!
wait $scalar_pid || { echo "test-arm64: the scalar run failed" >&2; exit 1; }
wait $neon_pid || { echo "test-arm64: the NEON run failed" >&2; exit 1; }
status=0
count=0
for png in "$work/x86"/*/*.png; do
    name=${png#"$work/x86"/}
    count=$((count + 1))
    for set in scalar neon; do
        if ! cmp -s "$png" "$work/$set/$name"; then
            echo "differs on AArch64 ($set) from x86-64: $name"
            status=1
        fi
    done
done
[ "$count" -gt 0 ] || { echo "test-arm64: no image rendered" >&2; exit 1; }
[ $status -eq 0 ] && echo "AArch64 scalar and NEON: $count images identical to x86-64's"
echo "test-arm64: $(($(date +%s) - start)) s"
exit $status
