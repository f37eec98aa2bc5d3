#!/bin/sh
# Runs under valgrind memcheck, with BUILD_DIR's programs: sgapi-render on every scene file of
# scenes/ and on two model files, a short turntable (its frames written on the writer threads),
# the example that creates and destroys objects between the frames of an animation
# (apps/examples/), and a regression run with a report, a JUnit file and a golden update. Any
# memory error or definite/indirect leak fails the run (exit 1); the images go to a scratch folder.
#
#   tools/memcheck.sh BUILD_DIR
set -eu
build=${1:?usage: tools/memcheck.sh BUILD_DIR}
src=$(cd "$(dirname "$0")/.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

memcheck() {
    valgrind --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite,indirect "$@"
}
# Every scene file but scale.json (millions of triangles a scene: for sgapi-bench).
# Every scene file in two runs side by side: memcheck runs a program's threads on one core.
half() { # K: every other scene file from the K-th (0 or 1), scale.json left out
    k=$1
    set --
    i=0
    for f in "$src"/scenes/*.json; do
        [ "${f##*/}" = scale.json ] && continue
        [ $((i % 2)) -eq "$k" ] && set -- "$@" "$f"
        i=$((i + 1))
    done
    memcheck "$build/apps/sgapi-render" "$@" -o "$out/$k"
}
half 0 &
first=$!
half 1
wait $first
memcheck "$build/apps/sgapi-render" "$src/scenes/default.json" --scene 03_pyramid_and_cube \
    -o "$out/turntable" --turntable 3
# A comparison with every regression output: a failing scene (another scene's golden), the
# thresholds file, the JUnit file, the report and a golden update (exit 0 once updated).
mkdir -p "$out/golden"
cp "$src/golden/01_colored_triangle.png" "$out/golden/02_tris_and_quads.png"
memcheck "$build/apps/sgapi-render" "$src/scenes/default.json" --scene 01_colored_triangle \
    --scene 02_tris_and_quads -o "$out/compare" --compare "$out/golden" \
    --thresholds "$src/golden/thresholds.csv" --junit "$out/junit.xml" --report "$out/report" \
    --update-golden
memcheck "$build/apps/examples/animate_objects" 200 32
# Model files: an OFF file with face colours, and an OBJ file with materials and textures (from
# Debian's assimp-testmodels, which the set-up installs).
memcheck "$build/apps/sgapi-render" "$src/scenes/assets/dodecahedron.off" \
    /usr/share/assimp/models/OBJ/spider.obj -o "$out/models" --size 320x240
